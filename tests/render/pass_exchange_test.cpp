// The frame loop's protocol between ranks (render/pass_exchange.h) without MPI: the ranks
// are threads of this process sharing mailboxes (ThreadCluster below), so these tests run
// in every build. Rank 0 must get every pass of the other ranks, in pass order and with
// their contents; a worker's failure must reach rank 0 as one RankFailure naming the rank,
// the cause and the exit code; and after stop() no rank may be left waiting and no message
// unreceived.
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "render/cluster.h"
#include "render/pass_exchange.h"
#include "util/error.h"

namespace tessera {
namespace {

// Messages in flight, per (from, to), in sending order (as MPI orders messages between
// two ranks on one communicator).
struct Mailboxes {
    std::mutex mutex;
    std::condition_variable arrived;
    std::map<std::pair<int, int>, std::deque<std::pair<RankMessage, std::vector<char>>>> queues;

    bool all_empty() {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& [key, q] : queues)
            if (!q.empty()) return false;
        return true;
    }
};

class ThreadCluster final : public Cluster {
public:
    ThreadCluster(Mailboxes& boxes, int rank, int size) : boxes_(boxes), rank_(rank), size_(size) {}
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    uint32_t broadcast(uint32_t) override { throw std::logic_error("not used by the pass exchange"); }
    void send(int to, RankMessage tag, const void* data, size_t bytes) override {
        const char* p = static_cast<const char*>(data);
        {
            std::lock_guard<std::mutex> lock(boxes_.mutex);
            boxes_.queues[{rank_, to}].emplace_back(tag, std::vector<char>(p, p + bytes));
        }
        boxes_.arrived.notify_all();
    }
    RankMessage receive(int from, std::vector<char>& data) override {
        std::unique_lock<std::mutex> lock(boxes_.mutex);
        auto& q = boxes_.queues[{from, rank_}];
        boxes_.arrived.wait(lock, [&] { return !q.empty(); });
        const RankMessage tag = q.front().first;
        data = std::move(q.front().second);
        q.pop_front();
        return tag;
    }
    bool waiting(int from, RankMessage tag) override {
        std::lock_guard<std::mutex> lock(boxes_.mutex);
        for (const auto& m : boxes_.queues[{from, rank_}])
            if (m.first == tag) return true;
        return false;
    }

protected:
    void agree(const std::exception_ptr&) override { throw std::logic_error("not used by the pass exchange"); }

private:
    Mailboxes& boxes_;
    int rank_, size_;
};

constexpr size_t kFloats = 6;  // a "pass" of six floats, each equal to its pass index

// Fills each pass with its index; throws `failure` at pass `fail_at`.
class IndexIntegrator final : public Integrator {
public:
    explicit IndexIntegrator(uint32_t fail_at = ~0u, std::exception_ptr failure = nullptr)
        : fail_at_(fail_at), failure_(std::move(failure)) {}
    void render_pass(const TsFrame& frame, std::vector<float>& out) override {
        if (frame.pass == fail_at_) std::rethrow_exception(failure_);
        out.assign(kFloats, float(frame.pass));
    }

private:
    uint32_t fail_at_;
    std::exception_ptr failure_;
};

// Workers 1..size-1 run run_worker on threads; their outcome (null: returned normally).
struct Workers {
    std::vector<std::thread> threads;
    std::vector<std::exception_ptr> outcome;
    std::vector<std::unique_ptr<ThreadCluster>> clusters;
    std::vector<std::unique_ptr<IndexIntegrator>> integrators;

    Workers(Mailboxes& boxes, int size, uint32_t first, uint32_t spp, int failing_rank = -1, uint32_t fail_at = ~0u,
            std::exception_ptr failure = nullptr)
        : outcome(size_t(size)) {
        for (int r = 1; r < size; ++r) {
            clusters.push_back(std::make_unique<ThreadCluster>(boxes, r, size));
            integrators.push_back(r == failing_rank ? std::make_unique<IndexIntegrator>(fail_at, failure)
                                                    : std::make_unique<IndexIntegrator>());
        }
        for (int r = 1; r < size; ++r)
            threads.emplace_back([this, r, first, spp] {
                try {
                    run_worker(*clusters[size_t(r - 1)], *integrators[size_t(r - 1)], TsFrame{}, first, spp);
                } catch (...) {
                    outcome[size_t(r)] = std::current_exception();
                }
            });
    }
    void join() {
        for (auto& t : threads) t.join();
    }
};

TEST(PassOwner, RoundRobinFromTheFirstPassRendered) {
    EXPECT_EQ(pass_owner(7, 7, 3), 0);
    EXPECT_EQ(pass_owner(8, 7, 3), 1);
    EXPECT_EQ(pass_owner(9, 7, 3), 2);
    EXPECT_EQ(pass_owner(10, 7, 3), 0);
    EXPECT_EQ(pass_owner(5, 0, 1), 0);
}

TEST(PassExchange, RankZeroGetsEveryOtherRanksPassInOrder) {
    Mailboxes boxes;
    const uint32_t first = 4, spp = 17;  // as after a checkpoint of 4 passes
    Workers workers(boxes, 3, first, spp);
    ThreadCluster lead(boxes, 0, 3);
    std::vector<uint32_t> received;
    {
        PassCollector collector(lead, kFloats);
        std::vector<float> pass;
        for (uint32_t i = first; i < spp; ++i) {
            const int owner = pass_owner(i, first, 3);
            if (owner == 0) continue;  // rank 0 renders these itself
            ASSERT_TRUE(collector.receive(owner, i, pass));
            ASSERT_EQ(pass, std::vector<float>(kFloats, float(i)));
            received.push_back(i);
        }
        collector.stop(0);
    }
    workers.join();
    EXPECT_EQ(received, (std::vector<uint32_t>{5, 6, 8, 9, 11, 12, 14, 15}));
    for (const auto& e : workers.outcome) EXPECT_FALSE(e);
    EXPECT_TRUE(boxes.all_empty());
}

TEST(PassExchange, WorkerFailureReachesRankZeroNamingTheRankAndCause) {
    Mailboxes boxes;
    // Rank 2 of 3 fails at pass 5 (its second pass); the others go on until stopped.
    Workers workers(boxes, 3, 0, 30, 2, 5, std::make_exception_ptr(RuntimeError("OpenCL device lost")));
    ThreadCluster lead(boxes, 0, 3);
    PassCollector collector(lead, kFloats);
    std::vector<float> pass;
    ASSERT_TRUE(collector.receive(1, 1, pass));
    ASSERT_TRUE(collector.receive(2, 2, pass));
    ASSERT_TRUE(collector.receive(1, 4, pass));
    try {
        collector.receive(2, 5, pass);
        FAIL() << "no RankFailure";
    } catch (const RankFailure& f) {
        EXPECT_STREQ(f.what(), "rank 2 of 3: OpenCL device lost");
        EXPECT_EQ(f.exit_code, 1);
        collector.stop(f.exit_code);
    }
    workers.join();
    for (int r : {1, 2}) {  // both end quietly with rank 0's exit code: rank 0 reports
        ASSERT_TRUE(workers.outcome[size_t(r)]) << "rank " << r;
        try {
            std::rethrow_exception(workers.outcome[size_t(r)]);
        } catch (const RankFailure& f) {
            EXPECT_TRUE(f.silent());
            EXPECT_EQ(f.exit_code, 1);
        }
    }
    EXPECT_TRUE(boxes.all_empty());
}

TEST(PassExchange, BadInputOnAWorkerKeepsExitCodeTwo) {
    Mailboxes boxes;
    Workers workers(boxes, 2, 0, 6, 1, 1, std::make_exception_ptr(InputError("texture wood.png: not found")));
    ThreadCluster lead(boxes, 0, 2);
    PassCollector collector(lead, kFloats);
    std::vector<float> pass;
    try {
        collector.receive(1, 1, pass);
        FAIL() << "no RankFailure";
    } catch (const RankFailure& f) {
        EXPECT_STREQ(f.what(), "rank 1 of 2: texture wood.png: not found");
        EXPECT_EQ(f.exit_code, 2);
        collector.stop(f.exit_code);
    }
    workers.join();
    EXPECT_TRUE(boxes.all_empty());
}

TEST(PassExchange, StopWhileWorkersRenderLeavesNoRankWaiting) {
    // Rank 0 fails (or is interrupted) after one pass: its collector's destructor stops the
    // workers, which are mid-render; they end with its exit code and nothing stays queued.
    Mailboxes boxes;
    Workers workers(boxes, 3, 0, 1000);
    ThreadCluster lead(boxes, 0, 3);
    {
        PassCollector collector(lead, kFloats);
        std::vector<float> pass;
        ASSERT_TRUE(collector.receive(1, 1, pass));
    }  // destructor: stop(1)
    workers.join();
    for (int r : {1, 2}) {
        ASSERT_TRUE(workers.outcome[size_t(r)]);
        EXPECT_EQ(exit_code_of(workers.outcome[size_t(r)]), 1);
    }
    EXPECT_TRUE(boxes.all_empty());
}

TEST(PassExchange, PassOutOfTurnIsAProtocolError) {
    Mailboxes boxes;
    Workers workers(boxes, 2, 0, 4);
    ThreadCluster lead(boxes, 0, 2);
    PassCollector collector(lead, kFloats);
    std::vector<float> pass;
    EXPECT_THROW(collector.receive(1, 3, pass), RuntimeError);  // pass 1 was due from rank 1
    collector.stop(1);
    workers.join();
}

}  // namespace
}  // namespace tessera
