// main.cpp — the fenestra command line, and the one place errors are reported.
//
// Every user-facing failure (bad input, unknown option, missing device, failed kernel build)
// arrives here as an exception and leaves as "fenestra: error: <message>" on stderr with exit
// status 1 (2 for command-line usage errors). Nothing is printed twice, nothing crashes.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>

#include "batch/batch_cmd.h"
#include "bench/bench.h"
#include "render/render_cmd.h"
#include "cl/cl_error.h"
#include "commands.h"
#include "emission/strategy_registry.h"
#include "trace/device_bvh.h"
#include "team/team.h"
#include "util/error.h"
#include "util/stop_signals.h"
#ifdef FEN_HAVE_MPI
#include "team/mpi_team.h"
#endif

namespace {

int fail(const std::string& message, int code)
{
    // Under mpirun the failing rank ends the job: no other waits for it in a collective. When every
    // rank fails alike (bad input), the root's line comes first and its abort ends the others
    // before they print theirs; a rank that fails alone says which it is.
    fen::Team& team = fen::processTeam();
    if (team.size() > 1 && !team.root() && !fen::lastCollectiveDone())
        std::this_thread::sleep_for(std::chrono::seconds(1));
    const std::string who = team.size() > 1 && !team.root() ? fen::cat("rank ", team.rank(), ": ") : "";
    // One line, whatever a message quotes: control characters are escaped here, at the boundary.
    std::fprintf(stderr, "fenestra: error: %s%s\n", who.c_str(), fen::printable(message, 4000).c_str());
#ifdef FEN_HAVE_MPI
    if (team.size() > 1 && !fen::lastCollectiveDone()) {
        std::fflush(stderr);
        fen::abortMpi(code);
    }
#endif
    return code;
}

std::vector<int> parseWidths(const std::string& s)
{
    if (s.empty())
        return {};
    if (s == "all")
        return {2, 4, 8};
    std::vector<int> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ',')) {
        const int width = fen::bvhLayoutWidth(item);
        if (width == 0)
            throw fen::Error("--layout takes bvh2, bvh4, bvh8, a comma-separated list or 'all', not '" +
                             item + "'");
        out.push_back(width);
    }
    return out;
}

}  // namespace

int main(int argc, char** argv)
{
#ifdef FEN_HAVE_MPI
    // Started by mpirun: this process is one rank of a team that shares a render's paths.
    std::unique_ptr<fen::Team> mpi;
    if (fen::launchedByMpi()) {
        try {
            mpi = fen::joinMpi(&argc, &argv);
        } catch (const fen::Error& e) {
            return fail(e.what(), 1);
        }
        fen::setProcessTeam(mpi.get());
        // a signal reaches every rank: one line says so, rank 0's
        fen::StopSignals::setQuiet(!mpi->root());
    }
#endif
    CLI::App app{"fenestra - light tracer for daylit interiors (OpenCL)", "fenestra"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "fenestra 0.1");

    bool devicesJson = false;
    auto* devices = app.add_subcommand("devices", "List OpenCL platforms and devices");
    devices->add_flag("--json", devicesJson, "Machine-readable output");

    fen::BenchOptions bench;
    std::string layouts;
    auto* benchCmd = app.add_subcommand(
        "bench", "Ray traversal throughput on the procedural room or a glTF scene, against Embree");
    benchCmd->add_option("scene", bench.scenePath,
                         "room (default: procedural 110k triangles), spheres (room + 100 spheres, "
                         "1.09M triangles) or a glTF file");
    benchCmd->add_option("--device", bench.device, "OpenCL device: index or name substring");
    benchCmd->add_option("--layout", layouts, "BVH layouts: bvh2, bvh4, bvh8, a list, or all "
                                              "(default: the device's)");
    benchCmd->add_option("--rays", bench.rays, "Rays per query (default 4194304)");
    benchCmd->add_option("--runs", bench.runs, "Counted runs (default 5)");
    benchCmd->add_option("--warmup", bench.warmup, "Uncounted runs first (default 1)");
    benchCmd->add_option("--seed", bench.seed, "Seed of the rays");
    bool noEmbree = false;
    benchCmd->add_flag("--no-embree", noEmbree, "Skip the Embree comparison");
    benchCmd->add_flag("--sweep-quality", bench.sweepQuality,
                       "Also build a full-sweep SAH tree and compare SAH costs");
    benchCmd->add_flag("--json", bench.json, "Machine-readable output");
    benchCmd->add_flag("--render", bench.render,
                       "Also render the scene each round (procedural scenes get an opening and "
                       "lights) and compare its rays/s with traversal");
    benchCmd->add_option("--render-paths", bench.renderPaths, "Light paths per render instead of --render-time");
    benchCmd->add_option("--render-time", bench.renderSeconds, "Seconds per render (default 20)");
    benchCmd->add_option("--render-method", bench.renderMethod, "Emission method of the render (default uniform)");
    benchCmd->add_option("--kernels", bench.kernels, "Render kernels: fused or wavefront (default: the device's)");

    fen::FalseColorOptions falseColor;
    auto* falseColorCmd = app.add_subcommand(
        "falsecolor", "An EXR's luminance or a sensor file's planes in false colour, on a labelled scale (PNG)");
    fen::addFalseColorOptions(*falseColorCmd, falseColor);

    fen::RenderOptions render;
    auto* renderCmd = app.add_subcommand("render", "Light-trace a glTF scene to EXR + PNG + JSON");
    fen::addRenderOptions(*renderCmd, render);

    fen::BatchOptions batch;
    auto* batchCmd = app.add_subcommand("batch", "Run the renders of a jobs file (JSON) in one process");
    batchCmd->add_option("jobs", batch.jobsPath,
                         "The jobs file: {\"jobs\": [{\"name\": N, \"render\": [arguments of fenestra render]}, ...]}")
        ->required();
    batchCmd->add_option("--device", batch.device, "OpenCL device for every job: index or name substring");
    batchCmd->add_flag("--rerun", batch.rerun, "Run every job, also those finished and unchanged since");

    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        std::string names;
        for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
            known = known || sub->get_name() == argv[1];
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
        if (!known)
            return fail(std::string("unknown command '") + argv[1] + "' (commands: " + names + ")", 2);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // CLI11 quotes what was typed, bytes and all: one line, control characters escaped.
        return fail(fen::printable(e.what(), 400) + " (see fenestra --help)", 2);
    }

    if (fen::processTeam().size() > 1 && !*renderCmd && !*batchCmd)
        return fail(fen::cat("under mpirun only `fenestra render` and `fenestra batch` share their work over the "
                             "ranks (", fen::processTeam().describe(), "); run `fenestra ", argv[1],
                             "` as one process"),
                    2);
    try {
        if (*devices)
            return fen::runDevices(devicesJson);
        if (*renderCmd) {
            fen::validateRenderOptions(render);
            return fen::runRender(render);
        }
        if (*falseColorCmd)
            return fen::runFalseColor(falseColor);
        if (*batchCmd)
            return fen::runBatch(batch);
        if (*benchCmd) {
            bench.widths = parseWidths(layouts);
            bench.embree = !noEmbree;
            return fen::runBench(bench);
        }
    } catch (const fen::Error& e) {
        return fail(e.what(), 1);
    } catch (const cl::Error& e) {
        return fail("OpenCL: " + fen::ocl::describe(e), 1);
    } catch (const std::bad_alloc&) {
        return fail("out of host memory", 1);
    } catch (const std::exception& e) {
        return fail(e.what(), 1);
    }
    return 0;
}
