// Output that only appears when complete: write to "<path>.part", then rename over
// <path>. An interrupted or failed run leaves at most a ".part" file, never a file with
// the final name that looks finished. rename() within one directory is atomic on POSIX.
//
// A failed run removes only a ".part" it can prove is its own: one that was not there
// when it started. A ".part" found at the start (an interrupted run's, perhaps one that
// --restart can continue) is never removed by a failure; a successful run renames its
// own over the final name as usual.
#pragma once
#include <string>

namespace flotsam {

class AtomicOutput {
public:
    explicit AtomicOutput(std::string final_path);
    ~AtomicOutput();  // removes the partial file unless commit() or keep_partial() was called, or it predates this object
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    const std::string& temp_path() const { return temp_; }
    const std::string& final_path() const { return final_; }
    void commit();                         // rename temp -> final; throws naming both paths on failure
    void keep_partial() { keep_ = true; }  // leave the .part (a checkpointed run resumes from it)

private:
    std::string final_;
    std::string temp_;
    bool done_ = false;
    bool keep_ = false;
    bool temp_existed_ = false;  // a ".part" was there before: not ours to remove
};

// Writes `text` to `path` atomically.
void write_text_atomic(const std::string& path, const std::string& text);

// Creates the parent directory of `path` when it is missing.
void ensure_parent_dir(const std::string& path);

}  // namespace flotsam
