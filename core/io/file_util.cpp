#include "core/io/file_util.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "core/errors.h"

namespace trilab {

std::string read_file_bytes(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw IoError(path, 0, std::string("cannot open: ") + std::strerror(errno));
    std::string data;
    char buf[1 << 16];
    std::size_t n;
    if (std::fseek(f, 0, SEEK_END) == 0) {
        const long size = std::ftell(f);
        if (size > 0) data.reserve(static_cast<std::size_t>(size));
        std::fseek(f, 0, SEEK_SET);
    }
    while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) data.append(buf, n);
    const bool failed = std::ferror(f) != 0;
    std::fclose(f);
    if (failed) throw IoError(path, 0, "read error");
    return data;
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
    std::random_device rd;
    const std::string tmp = path + ".tmp" + std::to_string(rd() % 1000000);
    try {
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out)
                throw IoError(path, 0,
                              std::string("cannot create a temporary file beside it: ") +
                                  std::strerror(errno));
            write(out);
            out.close();  // close() flushes; its failure is a write error too
            if (out.fail()) throw IoError(path, 0, "write error (disk full?)");
        }
        // The new file keeps the permissions of the one it replaces.
        std::error_code ec;
        const std::filesystem::file_status old = std::filesystem::status(path, ec);
        if (!ec && std::filesystem::is_regular_file(old))
            std::filesystem::permissions(tmp, old.permissions(), ec);
        if (std::rename(tmp.c_str(), path.c_str()) != 0)
            throw IoError(path, 0, std::string("cannot replace the file: ") + std::strerror(errno));
    } catch (...) {
        std::remove(tmp.c_str());
        throw;
    }
}

HalfedgeMesh build_mesh_for_file(const PolygonSoup& soup, LoadReport& report,
                                 const std::string& path) {
    if (soup.positions.empty()) throw IoError(path, 0, "the file holds no vertices");
    try {
        return build_mesh(soup, report);
    } catch (const IoError&) {
        throw;
    } catch (const Error& e) {
        throw IoError(path, 0, e.what());
    }
}

void check_declared_count(std::size_t count, std::size_t min_bytes_each,
                          std::size_t available_bytes, const char* what, const std::string& path,
                          std::size_t line) {
    if (min_bytes_each == 0) min_bytes_each = 1;
    if (count > available_bytes / min_bytes_each)
        throw IoError(path, line,
                      "the header declares " + std::to_string(count) + " " + what +
                          ", more than the file's " + std::to_string(available_bytes) +
                          " bytes can hold");
}

}  // namespace trilab

#include <charconv>

namespace trilab {

void append_number(std::string& out, double value) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof(buf), value);
    out.append(buf, res.ptr);
}

void append_number(std::string& out, float value) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof(buf), value);
    out.append(buf, res.ptr);
}

void append_number(std::string& out, std::size_t value) {
    char buf[24];
    auto res = std::to_chars(buf, buf + sizeof(buf), value);
    out.append(buf, res.ptr);
}

}  // namespace trilab
