#include "image/background_writer.h"

#include <chrono>
#include <memory>
#include <system_error>
#include <utility>

namespace tessera {

BackgroundWriter::~BackgroundWriter() {
    if (!in_flight_.valid()) return;
    try {
        in_flight_.get();
    } catch (...) {  // a destructor must not throw; see the header
    }
}

void BackgroundWriter::start(std::function<void()> write) {
    wait();
    // Shared, not moved into std::async: where async throws, the write is still whole here.
    const auto task = std::make_shared<std::function<void()>>(std::move(write));
    try {
        in_flight_ = std::async(std::launch::async, [task] { (*task)(); });
    } catch (const std::system_error&) {  // no thread to be had (a process limit): write here
        (*task)();
    }
}

void BackgroundWriter::check() {
    if (in_flight_.valid() && in_flight_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) wait();
}

void BackgroundWriter::wait() {
    if (!in_flight_.valid()) return;
    std::future<void> done = std::move(in_flight_);  // invalid now, even if get() throws
    done.get();
}

}  // namespace tessera
