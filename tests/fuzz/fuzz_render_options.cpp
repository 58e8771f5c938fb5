// fuzz_render_options.cpp — libFuzzer entry: any bytes as the arguments of `fenestra render`
// (one argument a line, bytes of any value), through everything that reads them before a render
// starts: CLI11's parsing with the render command's options (render/render_options.h), their
// validation, every strategy's option block (emission/emission_options.h), the sky and sun
// options over a small scene (sky/sky_sun_options.h, with the moment's parsing and the solar
// position), the regions and ROI, and the JSON the names go into (io/json_text.h).
//
// Acceptable outcomes: a valid set of options, or a one-line fen::Error or CLI11 parse error. Any
// other exception, a crash, a sanitizer report, a message with a control character, or a JSON
// dump that throws is a finding. Usage: scripts/fuzz.sh --target options.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "io/json_text.h"
#include "render/image_stats.h"
#include "render/render_options.h"
#include "fuzz_checks.h"
#include "util/error.h"

namespace {

using fen::fuzz::requireOneLine;

fen::Scene litScene()
{
    fen::Scene s;
    s.source = "fuzz.gltf";
    s.sun.present = true;
    s.sun.nodeName = "sun";
    s.sun.travelDirection = glm::normalize(glm::dvec3(0.3, -0.8, 0.5));
    s.sun.illuminanceRgb_lux = glm::dvec3(80000.0);
    s.sky.type = fen::SkySpec::Type::Cie;
    s.sky.where = "fuzz.gltf: scenes[0].extras.sky";
    s.sky.cieType = 12;
    s.sky.zenithLuminance_cd_m2 = 3000.0;
    s.sky.sunAltitudeDeg = 53.0;
    s.sky.sunAzimuthDeg = 150.0;
    return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::vector<std::string> args = {"fenestra", "render"};
    std::string token;
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == '\n') {
            args.push_back(token);
            token.clear();
        } else {
            token += static_cast<char>(data[i]);
        }
    }
    args.push_back(token);
    if (args.size() > 64)
        return 0;
    std::vector<char*> argv;
    for (auto& a : args)
        argv.push_back(a.data());
    CLI::App app{"fuzz", "fenestra"};
    auto* render = app.add_subcommand("render", "");
    fen::RenderOptions o;
    fen::addRenderOptions(*render, o);
    try {
        app.parse(static_cast<int>(argv.size()), argv.data());
        fen::validateRenderOptions(o);
        const fen::EmissionSettings emission = o.emission.settings();
        (void)emission;
        fen::Scene scene = litScene();
        const fen::SkySunReport report = fen::applySkySunOptions(o.skySun, &scene);
        for (const std::string& w : report.warnings)
            requireOneLine(w);
        const fen::Roi roi = fen::parseRoi(o.roi.value_or(""), 640, 480);
        (void)roi;
        nlohmann::json names = {{"scene", o.scenePath}, {"out", o.outPath}, {"camera", o.camera}, {"device", o.device}};
        for (const std::string& r : o.regions)
            names["regions"][r] = r;
        if (o.checkpointPath)
            names["checkpoint"] = *o.checkpointPath;
        const std::string dumped = fen::dumpUtf8(names, 2);
        if (!nlohmann::json::accept(dumped))
            __builtin_trap();
    } catch (const CLI::CallForHelp&) {
    } catch (const CLI::CallForAllHelp&) {
    } catch (const CLI::CallForVersion&) {
    } catch (const CLI::ParseError& e) {
        requireOneLine(fen::printable(e.what(), 400));  // as host/main.cpp reports it
    } catch (const fen::Error& e) {
        requireOneLine(e.what());
    }
    return 0;
}
