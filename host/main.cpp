// main.cpp — the fenestra command line, and the one place errors are reported.
//
// Every user-facing failure (bad input, unknown option, missing device, failed kernel build)
// arrives here as an exception and leaves as "fenestra: error: <message>" on stderr with exit
// status 1 (2 for command-line usage errors). Nothing is printed twice, nothing crashes.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "bench/bench.h"
#include "render/render_cmd.h"
#include "cl/cl_error.h"
#include "commands.h"
#include "emission/strategy_registry.h"
#include "util/error.h"

namespace {

int fail(const std::string& message, int code)
{
    std::fprintf(stderr, "fenestra: error: %s\n", message.c_str());
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
        if (item == "2" || item == "bvh2")
            out.push_back(2);
        else if (item == "4" || item == "bvh4")
            out.push_back(4);
        else if (item == "8" || item == "bvh8")
            out.push_back(8);
        else
            throw fen::Error("--layout takes bvh2, bvh4, bvh8, a comma-separated list or 'all', not '" +
                             item + "'");
    }
    return out;
}

}  // namespace

int main(int argc, char** argv)
{
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

    fen::RenderOptions render;
    std::string renderLayout;
    bool progressOn = false, progressOff = false;
    auto* renderCmd = app.add_subcommand("render", "Light-trace a glTF scene to EXR + PNG + JSON");
    renderCmd->add_option("scene", render.scenePath, "glTF scene (.gltf or .glb)")->required();
    renderCmd->add_option("--out", render.outPath, "Output PATH.exr (PATH.png and PATH.json beside it)")
        ->required();
    // Signed, so that a negative count is an error rather than 2^64 - 1.
    std::int64_t renderPaths = 0;
    renderCmd->add_option("--paths", renderPaths, "Light paths to trace");
    renderCmd->add_option("--time", render.timeSeconds, "Render for about this many seconds instead");
    renderCmd->add_option("--width", render.width, "Image width (default: 640, or from --height)");
    renderCmd->add_option("--height", render.height, "Image height (default: from the camera's aspect ratio)");
    renderCmd->add_option("--camera", render.camera, "Camera node name (or camera name); default the first");
    renderCmd->add_option("--seed", render.seed, "Random seed (default 1)");
    renderCmd->add_option("--device", render.device, "OpenCL device: index or name substring");
    renderCmd->add_option("--max-bounces", render.maxBounces, "Surface interactions per path: a guard against endless paths, Russian roulette ends them (default 1024)");
    renderCmd->add_option("--roi", render.roi, "Region x0,y0,x1,y1 for the statistics (default: whole image)");
    renderCmd->add_option("--region", render.regions,
                          "Named region NAME=x0,y0,x1,y1 also reported in the JSON (regions.NAME); repeatable");
    renderCmd->add_option("--reference", render.referencePath, "Reference EXR: report RMSE and relative MSE");
    render.emission.add(*renderCmd);  // --method, --portals and every strategy's options
    renderCmd->add_option("--layout", renderLayout, "BVH layout: bvh2, bvh4 or bvh8 (default: the device's)");
    renderCmd->add_option("--batches", render.batches, "Independent batches for the noise estimate (default 16)");
    renderCmd->add_option("--camera-spp", render.cameraSpp,
                          "Camera-pass samples per pixel per batch, for the sky seen directly (default 1)");
    renderCmd->add_option("--kernels", render.kernels,
                          "How the stages run: fused (one kernel per path, default on a CPU) or wavefront (default on a GPU)");
    std::string rouletteDefaults;  // each strategy's own (emission/strategy_registry.h)
    for (const fen::StrategyDescriptor* d : fen::emissionStrategies())
        rouletteDefaults += (rouletteDefaults.empty() ? "" : ", ") + std::to_string(d->rouletteDepth) + " for " + d->name;
    renderCmd->add_option("--roulette-depth", render.rouletteDepth,
                          "Russian roulette from this surface interaction on; before it every path goes on (default " +
                              rouletteDefaults + ")");
    renderCmd->add_option("--split", render.split,
                          "At its first diffuse hit, a path weighing k >= 2 times the mean emitted weight goes on as min(k, N) "
                          "branches of 1/k the weight (1: never; default 1)");
    renderCmd->add_option("--split-weight", render.splitWeight,
                          "With --split: the weight unit k counts in, as a multiple of the mean emitted weight (default 1)");
    renderCmd->add_option("--pool", render.poolSize, "Path slots on the device (default: 2^16 CPU, 2^21 GPU)");
    renderCmd->add_option("--exposure", render.exposure, "PNG preview exposure (default: ROI mean to mid-grey)");
    renderCmd->add_option("--checkpoint", render.checkpointPath,
                          "Save the render's state to this file now and then, and when interrupted");
    renderCmd->add_option("--checkpoint-every", render.checkpointEvery,
                          "How often: N min, N s or N batches (default 10min)");
    renderCmd->add_option("--resume", render.resumePath,
                          "Continue the render saved in this checkpoint (same scene and options)");
    fen::addSkySunOptions(renderCmd, &render.skySun);
    renderCmd->add_flag("--progress", progressOn, "Show progress even when stderr is not a terminal");
    renderCmd->add_flag("--no-progress", progressOff, "Never show progress");

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
        return fail(std::string(e.what()) + " (see fenestra --help)", 2);
    }

    try {
        if (*devices)
            return fen::runDevices(devicesJson);
        if (*renderCmd) {
            if (!renderLayout.empty()) {
                const auto w = parseWidths(renderLayout);
                if (w.size() != 1)
                    throw fen::Error("--layout takes one of bvh2, bvh4, bvh8");
                render.bvhWidth = w[0];
            }
            if (progressOff || progressOn)
                render.progress = !progressOff;
            if (renderCmd->count("--paths")) {
                if (renderPaths <= 0)
                    throw fen::Error("--paths " + std::to_string(renderPaths) + ": must be a positive number of paths");
                render.paths = static_cast<std::uint64_t>(renderPaths);
            }
            if (renderCmd->count("--exposure") && !(render.exposure > 0.0 && std::isfinite(render.exposure)))
                throw fen::Error("--exposure " + std::to_string(render.exposure) + ": must be a positive, finite multiplier");
            return fen::runRender(render);
        }
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
