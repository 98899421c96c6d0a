#pragma once
// JobRunner: runs one long operation at a time off the render thread. The job's work
// function runs on a worker thread and returns a "finish" function; the render thread calls
// that function when the job is done, so the document only changes on the render thread and
// only when a job succeeded. A failed or cancelled job changes nothing and leaves its reason.
//
//   runner.start("Loading bunny.obj", [path](Progress& p) {
//       LoadedMesh m = read_mesh(path);           // worker thread
//       return [m = std::move(m)]() mutable { ... };  // render thread, on success
//   });
//   runner.poll();  // each frame: applies a finished job, returns what happened
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "core/progress.h"

namespace trilab::viewer {

/// What a job is for (typed, never read from its name): a preview's outcome is the panel's,
/// any other job's is the document's.
enum class JobKind { Document, Preview };

class JobRunner {
public:
    using Finish = std::function<void()>;
    using Work = std::function<Finish(Progress&)>;

    /// What poll() found.
    struct Outcome {
        enum class Kind { None, Succeeded, Failed, Cancelled };
        Kind kind = Kind::None;
        std::string name;  ///< the job's name
        JobKind job = JobKind::Document;
        std::string message;  ///< the error for Failed
        double seconds = 0;   ///< wall time of the work
    };

    JobRunner() = default;
    /// Waits for a running job (after asking it to cancel).
    ~JobRunner();
    JobRunner(const JobRunner&) = delete;
    JobRunner& operator=(const JobRunner&) = delete;

    /// Starts a job. Returns false (and starts nothing) while another job runs.
    bool start(std::string name, Work work, JobKind kind = JobKind::Document);
    /// Asks the running job to stop. A job that cannot notice (a file read) finishes its work
    /// and its result is discarded.
    void cancel();
    bool busy() const { return state_ != nullptr; }
    /// On the render thread, once per frame: when the job is done, joins it and runs its
    /// finish function if it succeeded and was not cancelled.
    Outcome poll();

    /// The running job's name, progress fraction (negative when unknown) and stage.
    std::string name() const;
    /// The running job's kind (Document when none runs).
    JobKind kind() const;
    double fraction() const;
    std::string stage() const;
    double elapsed_seconds() const;
    bool cancel_requested() const;

private:
    struct State;
    std::shared_ptr<State> state_;
    std::thread thread_;
};

}  // namespace trilab::viewer
