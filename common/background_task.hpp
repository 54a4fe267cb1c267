// One background thread that runs one job at a time, for work that can overlap the
// caller's (the flow replay reads the next frame while the bodies step through this
// interval, debris/frame_source.hpp). start() hands it a job; wait() blocks until that
// job is done and returns what it threw (null if nothing). The thread starts with the
// first job and is joined by the destructor, after the job in hand.
//
// The caller keeps the job's data apart: between start() and wait() only the job
// touches it (wait() orders the job's writes before the caller's reads).
#pragma once
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace flotsam {

class BackgroundTask {
public:
    BackgroundTask() = default;
    ~BackgroundTask();
    BackgroundTask(const BackgroundTask&) = delete;
    BackgroundTask& operator=(const BackgroundTask&) = delete;

    void start(std::function<void()> job);  // waits for the job in hand first (its error is dropped)
    std::exception_ptr wait();              // null when no job was started
    bool busy() const;                      // a job was started and not yet waited for

private:
    void loop();

    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::function<void()> job_;
    std::exception_ptr error_;
    bool running_ = false;  // the job in hand is not finished
    bool waited_ = true;    // wait() has returned for the last job
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace flotsam
