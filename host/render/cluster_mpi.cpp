// The MPI cluster (render/cluster.h): compiled only when CMake finds MPI (TESSERA_MPI).
// Every call is made from the main thread (MPI_THREAD_FUNNELED); rendering threads (TBB,
// PoCL) never touch MPI.
#include <mpi.h>

#include <climits>
#include <memory>
#include <string>

#include "render/cluster.h"
#include "util/error.h"

namespace tessera {
namespace {

constexpr int kAgreeTag = 100;  // step() outcomes; apart from the frame loop's RankMessage tags

class MpiCluster final : public Cluster {
public:
    MpiCluster() {
        int provided = 0;
        if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
            throw RuntimeError("MPI_Init_thread failed (started by an MPI launcher, but MPI could not start)");
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
    ~MpiCluster() override { MPI_Finalize(); }

    int rank() const override { return rank_; }
    int size() const override { return size_; }

    uint32_t broadcast(uint32_t value) override {
        MPI_Bcast(&value, 1, MPI_UINT32_T, 0, MPI_COMM_WORLD);
        return value;
    }

    void send(int to, RankMessage tag, const void* data, size_t bytes) override {
        if (bytes > size_t(INT_MAX))
            throw RuntimeError("a pass of " + std::to_string(bytes) +
                               " bytes is too large for one MPI message (2 GiB); render a smaller image per job");
        MPI_Send(data, int(bytes), MPI_BYTE, to, int(tag), MPI_COMM_WORLD);
    }

    RankMessage receive(int from, std::vector<char>& data) override {
        MPI_Status status;
        MPI_Probe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
        int count = 0;
        MPI_Get_count(&status, MPI_BYTE, &count);
        data.resize(size_t(count));
        MPI_Recv(data.data(), count, MPI_BYTE, from, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        return RankMessage(status.MPI_TAG);
    }

    bool waiting(int from, RankMessage tag) override {
        int flag = 0;
        MPI_Iprobe(from, int(tag), MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
        return flag != 0;
    }

protected:
    // Rank 0 gathers every rank's exit code, then the messages of the failed ranks, and
    // broadcasts the lowest failing rank's code as the verdict.
    void agree(const std::exception_ptr& failure) override {
        int code = 0;
        std::string message;
        if (failure) {
            code = exit_code_of(failure);
            try {
                std::rethrow_exception(failure);
            } catch (const std::exception& e) {
                message = e.what();
            } catch (...) {
                message = "unknown failure";
            }
        }
        std::vector<int> codes(size_t(size_), 0);
        MPI_Gather(&code, 1, MPI_INT, codes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
        if (rank_ != 0 && code != 0)
            MPI_Send(message.data(), int(message.size()), MPI_CHAR, 0, kAgreeTag, MPI_COMM_WORLD);
        int verdict = 0;
        std::string report;
        if (rank_ == 0) {
            int failed = 0;
            for (int r = 0; r < size_; ++r) {
                if (codes[size_t(r)] == 0) continue;
                std::string text = message;
                if (r != 0) {
                    MPI_Status status;
                    MPI_Probe(r, kAgreeTag, MPI_COMM_WORLD, &status);
                    int count = 0;
                    MPI_Get_count(&status, MPI_CHAR, &count);
                    text.assign(size_t(count), '\0');
                    MPI_Recv(text.data(), count, MPI_CHAR, r, kAgreeTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                }
                if (failed++ == 0) {
                    verdict = codes[size_t(r)];
                    report = "rank " + std::to_string(r) + " of " + std::to_string(size_) + ": " + text;
                }
            }
            if (failed == size_ && size_ > 1)  // e.g. a bad option: the same cause everywhere
                report = message + " (on all " + std::to_string(size_) + " ranks)";
            else if (failed > 1)
                report += " (" + std::to_string(failed) + " of " + std::to_string(size_) +
                          " ranks failed; this is the lowest one's cause)";
        }
        MPI_Bcast(&verdict, 1, MPI_INT, 0, MPI_COMM_WORLD);
        if (verdict != 0) throw RankFailure(report, verdict);
    }

private:
    int rank_ = 0, size_ = 1;
};

}  // namespace

std::unique_ptr<Cluster> make_mpi_cluster() { return std::make_unique<MpiCluster>(); }

}  // namespace tessera
