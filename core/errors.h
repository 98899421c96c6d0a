#pragma once
// The few exception types the core throws. Every message names where (function, file, line
// or parameter) and why. Operations check their input before mutating anything, so a thrown
// error leaves the mesh as it was.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace trilab {

/// Base of every trilab error.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A parameter or argument outside its valid range (names the parameter).
class InvalidArgument : public Error {
public:
    using Error::Error;
};

/// A run that stopped before its end because its result could not be trusted (a diverging
/// iteration, a solve that missed its tolerance); names the iteration and the reason.
class RunStopped : public Error {
public:
    using Error::Error;
};

/// An operation that would break the mesh's connectivity invariants.
class TopologyError : public Error {
public:
    using Error::Error;
};

/// A file that cannot be read or written. `line` is 0 where no line applies (binary formats).
class IoError : public Error {
public:
    IoError(std::string file, std::size_t line, std::string reason)
        : Error(format(file, line, reason)),
          file_(std::move(file)),
          line_(line),
          reason_(std::move(reason)) {}
    const std::string& file() const { return file_; }
    std::size_t line() const { return line_; }
    const std::string& reason() const { return reason_; }

private:
    static std::string format(const std::string& file, std::size_t line,
                              const std::string& reason) {
        std::string s = file;
        if (line > 0) s += ":" + std::to_string(line);
        return s + ": " + reason;
    }
    std::string file_;
    std::size_t line_;
    std::string reason_;
};

}  // namespace trilab
