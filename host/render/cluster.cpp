#include "render/cluster.h"

#include <cstdlib>
#include <memory>

#include "util/error.h"

namespace tessera {

#ifdef TESSERA_HAS_MPI
std::unique_ptr<Cluster> make_mpi_cluster();  // render/cluster_mpi.cpp
#endif

namespace {

// One process: every collective is trivial and there is no other rank to talk to.
class SoloCluster final : public Cluster {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    uint32_t broadcast(uint32_t value) override { return value; }
    void send(int, RankMessage, const void*, size_t) override {
        throw std::logic_error("Cluster::send: a one-process render has no other rank");
    }
    RankMessage receive(int, std::vector<char>&) override {
        throw std::logic_error("Cluster::receive: a one-process render has no other rank");
    }
    bool waiting(int, RankMessage) override { return false; }

protected:
    void agree(const std::exception_ptr& failure) override {
        if (failure) std::rethrow_exception(failure);
    }
};

}  // namespace

bool launched_by_mpi() {
    if (!built_with_mpi()) return false;
    for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(var)) return true;
    return false;
}

int exit_code_of(const std::exception_ptr& e) {
    try {
        std::rethrow_exception(e);
    } catch (const RankFailure& f) {
        return f.exit_code;
    } catch (const InputError&) {
        return 2;
    } catch (const Interrupted&) {
        return 130;
    } catch (...) {
        return 1;
    }
}

void Cluster::step(const std::function<void()>& step) {
    stepped_ = true;
    if (size() == 1) return step();
    std::exception_ptr failure;
    try {
        step();
    } catch (...) {
        failure = std::current_exception();
    }
    agree(failure);
}

bool built_with_mpi() {
#ifdef TESSERA_HAS_MPI
    return true;
#else
    return false;
#endif
}

Cluster& world_cluster() {
    static const std::unique_ptr<Cluster> world = []() -> std::unique_ptr<Cluster> {
#ifdef TESSERA_HAS_MPI
        if (launched_by_mpi()) return make_mpi_cluster();
#endif
        return std::make_unique<SoloCluster>();
    }();
    return *world;
}

}  // namespace tessera
