// The per-pass cost of distributing a render (docs/distributed.md): under `mpirun -n 2`,
// rank 1 sends passes of a W x H image through the frame loop's own protocol
// (render/pass_exchange.h; its "integrator" only fills the buffer, so no time goes to
// rendering) and rank 0 receives each one and adds it to an Accumulator, as render_frame
// does. Prints the median seconds per pass of the receive (transfer plus copy) and of
// the add: on rank 0 they are paid once per pass rendered elsewhere.
//   mpirun -n 2 build/tessera_mpi_pass_bench [--width 512 --height 512 --passes 41]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <CLI/CLI.hpp>

#include "render/accumulator.h"
#include "render/cluster.h"
#include "render/pass_exchange.h"
#include "util/heap.h"

using namespace tessera;

namespace {

// Fills the pass with a constant: the message has the size of a real pass.
class FillIntegrator final : public Integrator {
public:
    explicit FillIntegrator(size_t floats) : floats_(floats) {}
    void render_pass(const TsFrame& frame, std::vector<float>& out) override { out.assign(floats_, 0.5f + frame.pass); }

private:
    size_t floats_;
};

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    tessera::keep_frame_memory();
    CLI::App app{"Per-pass cost of a distributed render's collection on rank 0 (run under mpirun -n 2)"};
    int width = 512, height = 512;
    uint32_t passes = 41;
    app.add_option("--width", width)->capture_default_str();
    app.add_option("--height", height)->capture_default_str();
    app.add_option("--passes", passes, "passes sent by rank 1")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    Cluster& cluster = world_cluster();
    if (cluster.size() != 2) {
        std::fprintf(stderr, "tessera_mpi_pass_bench: run it under mpirun -n 2 (this job has %d ranks)\n",
                     cluster.size());
        return 2;
    }
    const size_t floats = size_t(width) * height * TS_PASS_FLOATS;
    const uint32_t spp = 2 * passes;  // rank 1 owns the odd passes
    if (cluster.rank() == 1) {
        FillIntegrator fill(floats);
        run_worker(cluster, fill, TsFrame{}, 0, spp);
        return 0;
    }
    Accumulator acc(width, height);
    PassCollector collector(cluster, floats);
    std::vector<float> pass;
    std::vector<double> receive_s, add_s;
    using clock = std::chrono::steady_clock;
    for (uint32_t i = 1; i < spp; i += 2) {
        const auto t0 = clock::now();
        collector.receive(1, i, pass);
        const auto t1 = clock::now();
        acc.add(pass);
        receive_s.push_back(std::chrono::duration<double>(t1 - t0).count());
        add_s.push_back(std::chrono::duration<double>(clock::now() - t1).count());
    }
    collector.stop(0);
    std::printf("{\"width\": %d, \"height\": %d, \"pass_bytes\": %zu, \"passes\": %u, "
                "\"median_receive_s\": %.6f, \"median_add_s\": %.6f}\n",
                width, height, floats * sizeof(float) + 4, passes, median(receive_s), median(add_s));
    return 0;
}
