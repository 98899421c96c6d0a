#include "core/parallel.h"

#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>

#include <unistd.h>

#include "core/errors.h"

namespace trilab {

namespace {

/// 0: not set yet (the first thread_count() reads TRILAB_THREADS).
std::atomic<int> g_threads{0};

/// Whether this thread is running a block (a nested loop then runs in order, here).
thread_local bool t_in_block = false;

/// One loop in flight: its blocks, the next block to hand out, the first error.
struct Job {
    std::size_t blocks = 0;
    const std::function<void(std::size_t)>* body = nullptr;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex error_mutex;
    std::exception_ptr error;

    /// Takes blocks until none is left or one failed.
    void work() {
        t_in_block = true;
        for (std::size_t k; !failed.load(std::memory_order_relaxed) &&
                            (k = next.fetch_add(1, std::memory_order_relaxed)) < blocks;) {
            try {
                (*body)(k);
            } catch (...) {
                std::lock_guard<std::mutex> lock(error_mutex);
                if (!error) error = std::current_exception();
                failed.store(true);
            }
        }
        t_in_block = false;
    }
};

/// The pool: workers wait for a job's generation; the first `wanted` of them join it. Grows on
/// demand (thread_count() - 1 workers at most are used at once).
class Pool {
public:
    /// Runs `job` on the calling thread and `helpers` workers. False (nothing run) when another
    /// thread's job holds the pool.
    bool run(Job& job, int helpers) {
        // A child of fork() has none of the workers (and maybe a lock held at the fork): it
        // runs its loops in order on its one thread.
        if (::getpid() != owner_) return false;
        std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
        if (!busy.owns_lock()) return false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            while (int(workers_.size()) < helpers) {
                const int id = int(workers_.size());
                workers_.emplace_back([this, id] { loop(id); });
            }
            job_ = &job;
            wanted_ = helpers;
            active_ = helpers;
            ++generation_;
        }
        wake_.notify_all();
        job.work();
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [&] { return active_ == 0; });
        job_ = nullptr;
        return true;
    }

private:
    void loop(int id) {
        std::uint64_t seen = 0;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            seen = generation_;  // a worker started for a job joins it below
            if (job_ && id < wanted_) seen = generation_ - 1;
        }
        for (;;) {
            Job* job = nullptr;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return generation_ != seen; });
                seen = generation_;
                if (id >= wanted_) continue;
                job = job_;
            }
            job->work();
            {
                std::lock_guard<std::mutex> lock(mutex_);
                if (--active_ == 0) done_.notify_one();
            }
        }
    }

    const pid_t owner_ = ::getpid();  // the process whose threads these are
    std::mutex busy_;                 // held by the thread whose job is in flight
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::vector<std::thread> workers_;
    Job* job_ = nullptr;
    std::uint64_t generation_ = 0;
    int wanted_ = 0, active_ = 0;
};

/// Never destroyed: its workers wait for work until the process ends (a destructor would have
/// to join them at exit, and a forked child, which has none of them, could not).
Pool& pool() {
    static Pool* p = new Pool;
    return *p;
}

int from_environment() {
    const char* env = std::getenv("TRILAB_THREADS");
    if (!env || !*env) return 0;
    try {
        return parse_thread_count(env, "TRILAB_THREADS");
    } catch (const InvalidArgument&) {
        return 0;
    }
}

}  // namespace

int hardware_threads() {
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : int(n);
}

int thread_count() {
    int n = g_threads.load(std::memory_order_relaxed);
    if (n > 0) return n;
    n = from_environment();
    if (n == 0) n = hardware_threads();
    int expected = 0;
    g_threads.compare_exchange_strong(expected, n);
    return g_threads.load(std::memory_order_relaxed);
}

void set_thread_count(int n) {
    if (n < 0 || n > kMaxThreads)
        throw InvalidArgument("threads: expected 0 (every core) to " + std::to_string(kMaxThreads) +
                              ", got " + std::to_string(n));
    g_threads.store(n == 0 ? hardware_threads() : n);
}

int parse_thread_count(const std::string& text, const std::string& what) {
    const std::string reason = what + ": expected a whole number from 1 to " +
                               std::to_string(kMaxThreads) + " (0: every core), got '" + text + "'";
    if (text.empty() || text.size() > 6 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        throw InvalidArgument(reason);
    const int n = std::stoi(text);
    if (n > kMaxThreads) throw InvalidArgument(reason);
    return n;
}

void apply_thread_environment() {
    const char* env = std::getenv("TRILAB_THREADS");
    if (!env || !*env) return;
    set_thread_count(parse_thread_count(env, "TRILAB_THREADS"));
}

namespace detail {

bool in_block() {
    return t_in_block;
}

void run_blocks(std::size_t blocks, const std::function<void(std::size_t)>& body) {
    const int threads = thread_count();
    Job job;
    job.blocks = blocks;
    job.body = &body;
    const bool nested = t_in_block;
    const int helpers = int(std::min<std::size_t>(std::size_t(threads), blocks)) - 1;
    if (nested || helpers <= 0 || !pool().run(job, helpers)) {
        for (std::size_t k = 0; k < blocks; ++k) body(k);  // in order, here
        return;
    }
    if (job.error) std::rethrow_exception(job.error);
}

}  // namespace detail

}  // namespace trilab
