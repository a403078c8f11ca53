#include "render/pass_exchange.h"

#include <cstring>
#include <string>

#include "render/interrupt.h"
#include "util/error.h"

namespace tessera {
namespace {

bool terminal(RankMessage tag) {
    return tag == RankMessage::Done || tag == RankMessage::Error || tag == RankMessage::Interrupt;
}

std::string rank_name(const Cluster& c, int rank) {
    return "rank " + std::to_string(rank) + " of " + std::to_string(c.size());
}

int read_int(const std::vector<char>& data) {
    int v = 1;
    if (data.size() >= sizeof v) std::memcpy(&v, data.data(), sizeof v);
    return v;
}

}  // namespace

PassCollector::PassCollector(Cluster& cluster, size_t pass_floats)
    : cluster_(cluster), pass_floats_(pass_floats), finished_(size_t(cluster.size()), false) {}

PassCollector::~PassCollector() { stop(1); }

bool PassCollector::receive(int rank, uint32_t pass, std::vector<float>& out) {
    const RankMessage tag = cluster_.receive(rank, buffer_);
    if (terminal(tag)) finished_[size_t(rank)] = true;
    if (tag == RankMessage::Interrupt) return false;
    if (tag == RankMessage::Error) {
        const std::string cause = buffer_.size() > sizeof(int) ? std::string(buffer_.begin() + sizeof(int), buffer_.end())
                                                               : std::string("unknown failure");
        throw RankFailure(rank_name(cluster_, rank) + ": " + cause, read_int(buffer_));
    }
    uint32_t index = 0;
    if (tag == RankMessage::Pass && buffer_.size() == sizeof index + pass_floats_ * sizeof(float))
        std::memcpy(&index, buffer_.data(), sizeof index);
    if (tag != RankMessage::Pass || index != pass || buffer_.size() != sizeof index + pass_floats_ * sizeof(float))
        throw RuntimeError(rank_name(cluster_, rank) + " sent message " + std::to_string(int(tag)) + " of " +
                           std::to_string(buffer_.size()) + " bytes where pass " + std::to_string(pass) +
                           " was due (do all ranks run the same tessera with the same settings?)");
    out.resize(pass_floats_);
    std::memcpy(out.data(), buffer_.data() + sizeof index, pass_floats_ * sizeof(float));
    return true;
}

void PassCollector::stop(int exit_code) noexcept {
    if (stopped_) return;
    stopped_ = true;
    try {
        for (int r = 1; r < cluster_.size(); ++r) cluster_.send(r, RankMessage::Stop, &exit_code, sizeof exit_code);
        // A worker may be sending a pass or still rendering one: take what it sends until
        // its last message, so that it sees Stop and no message is left unreceived.
        for (int r = 1; r < cluster_.size(); ++r)
            while (!finished_[size_t(r)])
                if (terminal(cluster_.receive(r, buffer_))) finished_[size_t(r)] = true;
    } catch (...) {
        // MPI errors abort the job by default; nothing else here throws.
    }
}

void run_worker(Cluster& cluster, Integrator& integrator, TsFrame frame, uint32_t first, uint32_t spp) {
    std::vector<char> message;
    int stop_code = -1;
    auto stop_arrived = [&] {
        if (stop_code < 0 && cluster.waiting(0, RankMessage::Stop)) {
            cluster.receive(0, message);
            stop_code = read_int(message);
        }
        return stop_code >= 0;
    };
    RankMessage last = RankMessage::Done;
    std::vector<float> pass;
    try {
        for (uint64_t i = uint64_t(first) + uint64_t(cluster.rank()); i < spp; i += uint64_t(cluster.size())) {
            if (stop_arrived()) break;
            if (interrupt_signal()) {
                last = RankMessage::Interrupt;
                break;
            }
            frame.pass = uint32_t(i);
            integrator.render_pass(frame, pass);
            const uint32_t index = uint32_t(i);
            message.resize(sizeof index + pass.size() * sizeof(float));
            std::memcpy(message.data(), &index, sizeof index);
            std::memcpy(message.data() + sizeof index, pass.data(), pass.size() * sizeof(float));
            cluster.send(0, RankMessage::Pass, message.data(), message.size());
        }
    } catch (const std::exception& e) {
        last = RankMessage::Error;
        const int code = exit_code_of(std::current_exception());
        const std::string cause = e.what();
        message.resize(sizeof code + cause.size());
        std::memcpy(message.data(), &code, sizeof code);
        std::memcpy(message.data() + sizeof code, cause.data(), cause.size());
    }
    if (last == RankMessage::Error)
        cluster.send(0, last, message.data(), message.size());
    else
        cluster.send(0, last, nullptr, 0);
    while (stop_code < 0)
        if (cluster.receive(0, message) == RankMessage::Stop) stop_code = read_int(message);
    if (stop_code != 0) throw RankFailure("", stop_code);
}

}  // namespace tessera
