#include "common/background_task.hpp"

namespace flotsam {

BackgroundTask::~BackgroundTask() {
    {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return !running_; });
        stop_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void BackgroundTask::start(std::function<void()> job) {
    {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return !running_; });
        job_ = std::move(job);
        error_ = nullptr;
        running_ = true;
        waited_ = false;
    }
    if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });
    changed_.notify_all();
}

std::exception_ptr BackgroundTask::wait() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return !running_; });
    waited_ = true;
    return error_;
}

bool BackgroundTask::busy() const {
    std::lock_guard lock(mutex_);
    return !waited_;
}

void BackgroundTask::loop() {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return stop_ || running_; });
        if (!running_) return;  // stop_ with no job in hand
        std::function<void()> job = std::move(job_);
        lock.unlock();
        std::exception_ptr error;
        try {
            job();
        } catch (...) {
            error = std::current_exception();
        }
        lock.lock();
        error_ = error;
        running_ = false;
        changed_.notify_all();
    }
}

}  // namespace flotsam
