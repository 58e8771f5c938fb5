// adaptive_options.cpp — the `adaptive` strategy's option block, ranges and fingerprint
// (adaptive_options.h).
#include "emission/adaptive_options.h"

#include <initializer_list>
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "emission/strategy_registry.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace fen {

namespace {

constexpr struct {
    const char* name;
    GridEstimate estimate;
} kEstimates[] = {{"larger", GridEstimate::Larger}, {"pooled", GridEstimate::Pooled}, {"squares", GridEstimate::Squares}};

// "on" | "off" style choices: the value, or a one-line error naming the option.
bool choice(const std::string& option, const std::string& given, const char* yes, const char* no)
{
    if (given == yes || given == no)
        return given == yes;
    throw Error(cat(option, " '", printable(given, 40), "': expected ", yes, " or ", no));
}

// The first given of a group of options (in the order listed: the one an error names), or nullptr
// when none was given.
const char* firstGiven(std::initializer_list<std::pair<bool, const char*>> options)
{
    for (const auto& [given, name] : options)
        if (given)
            return name;
    return nullptr;
}

class AdaptiveOptionBlock final : public StrategyOptionBlock {
public:
    void add(CLI::App& render) override
    {
        render.add_option("--base", base_,
                          "With adaptive: the base density it learns over, uniform (default) or portal");
        render.add_option("--adaptive-initial-sky-depth", initialSkyDepth_,
                          "With adaptive: sky direction boxes to start with, 4^depth (default 1)");
        render.add_option("--adaptive-max-sky-depth", maxSkyDepth_,
                          "With adaptive: finest sky direction boxes, 2^-depth of a side (default 6)");
        render.add_option("--adaptive-estimate", estimate_,
                          "With adaptive: how a cell's second moment is estimated, larger (default: the larger of "
                          "pooled and squares), pooled (from first moments) or squares");
        render.add_option("--adaptive-initial-depth", initialDepth_,
                          "With adaptive: origin boxes per region to start with, 4^depth (default 3)");
        render.add_option("--adaptive-max-depth", maxDepth_,
                          "With adaptive: finest origin boxes, 2^-depth of the region's side (default 10)");
        render.add_option("--adaptive-defensive", defensive_,
                          "With adaptive: share of the base density kept in the mixture (default 0.1)");
        render.add_option("--adaptive-disk-share", diskShare_,
                          "With adaptive --base portal: the emission disk's share of the base (default 0.1)");
        render.add_option("--adaptive-split", split_,
                          "With adaptive: split a cell when that lowers the learned objective by this share (default 1/2048)");
        render.add_option("--adaptive-first-pass", firstPass_,
                          "With adaptive: paths of the first learning pass; passes double (default 65536)");
        render.add_option("--adaptive-prior", prior_,
                          "With adaptive: pseudo-paths of the prior in every cell (default 32)");
        render.add_option("--adaptive-weights", weights_,
                          "With adaptive: batches weigh by predicted precision, or all alike: predicted (default) or equal");
        render.add_option("--adaptive-guide", guide_,
                          "With adaptive: also learn where the first bounce sends light to the camera, on or off (default on)");
        render.add_option("--adaptive-guide-share", guideShare_,
                          "With adaptive --adaptive-guide on: the uniform share kept in every learned bounce table (default 0.25)");
        render.add_option("--adaptive-guide-voxels", guideVoxels_,
                          "With adaptive --adaptive-guide on: guide voxels across the scene's bounding radius, 1..16 (default 4; from 9 on the initial trees need --adaptive-guide-memory 1413 or more)");
        render.add_option("--adaptive-guide-depth", guideDepth_,
                          "With adaptive --adaptive-guide on: finest direction leaves, 2^-D of the square's side, 3..12 (3: a fixed 8 x 8)");
        render.add_option("--adaptive-guide-split", guideSplit_,
                          "With adaptive --adaptive-guide on: split a direction leaf holding more than this share of its slot (default 0.02)");
        render.add_option("--adaptive-guide-space-split", guideSpaceSplit_,
                          "With adaptive --adaptive-guide on: halve a spatial leaf whose slots gathered this many contributions in a pass (default 4096)");
        render.add_option("--adaptive-guide-min-gain", guideMinGain_,
                          "With adaptive --adaptive-guide on: steer a slot only where its table promises to cut the second moment this many times against the cosine, >= 1 (default 1)");
        render.add_option("--adaptive-guide-min-contributions", guideMinContributions_,
                          "With adaptive --adaptive-guide on: contributions a slot must have seen before its table may steer, >= 1 (default 32)");
        render.add_option("--adaptive-guide-vertices", guideVertices_,
                          "With adaptive --adaptive-guide on: the diffuse vertices the guide draws at, first (default) or every");
        render.add_option("--adaptive-window", window_,
                          "With adaptive --adaptive-guide on: weight windows -- split or cull a path at its first diffuse vertex by the root of its second moment of contributions (moment, the default) or its expected contribution (mean), or off");
        render.add_option("--adaptive-window-vertices", windowVertices_,
                          "With adaptive --adaptive-window mean|moment: where a path not split yet may split, at every diffuse vertex (default) or its first only");
        render.add_option("--adaptive-window-later", windowLater_,
                          "With adaptive --adaptive-window-vertices every: past the first vertex a path splits at this many times less weight than its slot's window, 1..64 (default 4)");
        render.add_option("--adaptive-window-split", windowSplit_,
                          "With adaptive --adaptive-window mean|moment: most branches a path splits into, 2..255 (default 16)");
        render.add_option("--adaptive-window-survival", windowSurvival_,
                          "With adaptive --adaptive-window mean|moment: least probability a path below its window survives with, (0, 1]; 1 (default): never culled");
        render.add_option("--adaptive-aim", aim_,
                          "With adaptive: aim the bounces outside at the glass that leads to the camera, learned, on or off (default on)");
        render.add_option("--adaptive-aim-share", aimShare_,
                          "With adaptive --adaptive-aim on: the cosine's share at an aimed vertex, a number in (0, 1) (default 0.75), or learned: at a path's first diffuse vertex, from what the paths deliver (0.75 past it; needs weight windows)");
        render.add_option("--adaptive-aim-share-min", aimShareMin_,
                          "With adaptive --adaptive-aim-share learned: the least share it learns, (0, 1) (default 0.25)");
        render.add_option("--adaptive-aim-share-max", aimShareMax_,
                          "With adaptive --adaptive-aim-share learned: the most share it learns, [min, 1] (default 0.95)");
        render.add_option("--adaptive-aim-power", aimPower_,
                          "With adaptive --adaptive-aim on: weigh each opening by its learned worth to this power, (0, 2] (default 1)");
        render.add_option("--adaptive-openings-share", openingsShare_,
                          "With adaptive --adaptive-aim on: the share of paths that start on the aimed panes and take the light reflected outside by walking outwards, [0, 1), or auto: chosen by the render from one pass raced in halves, at share 0 and 0.5 (default auto; 0: none)");
        render.add_option("--adaptive-openings-race-paths", openingsRacePaths_,
                          "With adaptive --adaptive-openings-share auto: the least pass, in paths, that the race runs in two halves (share 0, then 0.5), 2^16..2^40 (default 4194304)");
        render.add_option("--adaptive-guide-memory", guideMemory_,
                          "With adaptive --adaptive-guide on: MiB of device memory for the guide's trees (default 256)");
        render.add_option("--adaptive-target", target_,
                          "With adaptive: minimise the absolute (default) or the relative squared error per pixel");
        render.add_option("--adaptive-max-cells", maxCells_,
                          "With adaptive: most cells the grid may have (default 32768)");
    }

    void apply(EmissionSettings& e, bool inUse) const override
    {
        AdaptiveOptions& a = e.adaptive;
        if (base_) {
            a.base = parseEmissionMethod(*base_);
            if (!inUse)
                throw Error("--base applies to --method adaptive");
            if (a.base == EmissionMethod::Adaptive)
                throw Error("--base 'adaptive': expected uniform or portal");
        }
        const bool tuned = estimate_ || initialSkyDepth_ || maxSkyDepth_ || initialDepth_ || maxDepth_ ||
                           defensive_ || diskShare_ || split_ || firstPass_ || maxCells_ || prior_ || weights_ ||
                           target_ || guide_ || guideShare_ || guideVoxels_ || guideDepth_ || guideSplit_ || guideSpaceSplit_ || guideMemory_ || guideMinGain_ ||
                           guideMinContributions_ ||
                           guideVertices_ || window_ || windowSplit_ || windowSurvival_ || windowVertices_ || windowLater_ || aim_ ||
                           aimShare_ || aimPower_ || aimShareMin_ || aimShareMax_ || openingsShare_ || openingsRacePaths_;
        if (tuned && !inUse)
            throw Error("the --adaptive-* options apply to --method adaptive");
        if (!inUse)
            return;
        if (estimate_) {
            const GridEstimate* e = estimateNamed(*estimate_);
            if (!e)
                throw Error(cat("--adaptive-estimate '", printable(*estimate_, 40),
                                "': expected larger, pooled or squares"));
            a.estimate = *e;
        }
        a.initialSkyDepth = initialSkyDepth_.value_or(a.initialSkyDepth);
        a.maxSkyDepth = maxSkyDepth_.value_or(a.maxSkyDepth);
        a.initialDepth = initialDepth_.value_or(a.initialDepth);
        a.maxDepth = maxDepth_.value_or(a.maxDepth);
        a.defensive = defensive_.value_or(a.defensive);
        a.diskShare = diskShare_.value_or(a.diskShare);
        a.splitGain = split_.value_or(a.splitGain);
        a.firstPass = firstPass_.value_or(a.firstPass);
        a.maxCells = maxCells_.value_or(a.maxCells);
        a.priorPaths = prior_.value_or(a.priorPaths);
        if (weights_)
            a.weighBatches = choice("--adaptive-weights", *weights_, "predicted", "equal");
        if (target_)
            a.relativeTarget = choice("--adaptive-target", *target_, "relative", "absolute");
        if (guide_)
            a.guide.enabled = choice("--adaptive-guide", *guide_, "on", "off");
        a.guide.share = guideShare_.value_or(a.guide.share);
        a.guide.voxelsAcross = guideVoxels_.value_or(a.guide.voxelsAcross);
        a.guide.maxDepth = guideDepth_.value_or(a.guide.maxDepth);
        a.guide.splitShare = guideSplit_.value_or(a.guide.splitShare);
        a.guide.spatialSplitConnections = guideSpaceSplit_.value_or(a.guide.spatialSplitConnections);
        a.guide.memoryMiB = guideMemory_.value_or(a.guide.memoryMiB);
        a.guide.minGain = guideMinGain_.value_or(a.guide.minGain);
        a.guide.minConnections = guideMinContributions_.value_or(a.guide.minConnections);
        if (guideVertices_)
            a.guide.everyVertex = choice("--adaptive-guide-vertices", *guideVertices_, "every", "first");
        if (window_) {
            if (*window_ != "off" && *window_ != "mean" && *window_ != "moment")
                throw Error(cat("--adaptive-window '", printable(*window_, 40), "': expected off, mean or moment"));
            a.guide.window = *window_ != "off";
            a.guide.windowRule = *window_ == "moment" ? GuideOptions::WindowRule::Moment : GuideOptions::WindowRule::Mean;
        } else if (!a.guide.enabled) {
            a.guide.window = false;  // the default windows go with the guide they are learned on
        }
        a.guide.windowSplitMax = windowSplit_.value_or(a.guide.windowSplitMax);
        a.guide.windowMinSurvival = windowSurvival_.value_or(a.guide.windowMinSurvival);
        if (windowVertices_)
            a.guide.windowEveryVertex = choice("--adaptive-window-vertices", *windowVertices_, "every", "first");
        a.guide.windowLater = windowLater_.value_or(a.guide.windowLater);
        if (windowLater_ && !a.guide.windowEveryVertex)
            throw Error("--adaptive-window-later: applies past the first vertex, which --adaptive-window-vertices first turns off");
        const char* windowsOff = window_ ? "--adaptive-window off" : "--adaptive-guide off";
        if (const char* o = firstGiven({{windowSplit_.has_value(), "--adaptive-window-split"},
                                        {windowSurvival_.has_value(), "--adaptive-window-survival"},
                                        {windowLater_.has_value(), "--adaptive-window-later"},
                                        {windowVertices_.has_value(), "--adaptive-window-vertices"}});
            o && !a.guide.window)
            throw Error(cat(o, ": applies with weight windows, which ", windowsOff, " turns off"));
        if (a.guide.window && !a.guide.enabled)
            throw Error("--adaptive-window: needs --adaptive-guide on (the windows are learned with the guide)");
        if (aim_)
            a.aim.enabled = choice("--adaptive-aim", *aim_, "on", "off");
        if (const char* o = firstGiven({{aimShare_.has_value(), "--adaptive-aim-share"},
                                        {aimPower_.has_value(), "--adaptive-aim-power"},
                                        {openingsShare_.has_value(), "--adaptive-openings-share"},
                                        {openingsRacePaths_.has_value(), "--adaptive-openings-race-paths"},
                                        {aimShareMin_.has_value(), "--adaptive-aim-share-min"},
                                        {aimShareMax_.has_value(), "--adaptive-aim-share-max"}});
            o && !a.aim.enabled)
            throw Error(cat(o, ": applies with the opening aim, which --adaptive-aim off turns off"));
        if (aimShare_ && *aimShare_ == "learned") {
            a.aim.learnShare = true;
        } else if (aimShare_) {
            const std::optional<double> v = parseWholeNumber(*aimShare_);
            if (!v)
                throw Error(cat("--adaptive-aim-share '", printable(*aimShare_, 40), "': expected learned or a number in (0, 1)"));
            a.aim.learnShare = false;
            a.aim.cosineShare = *v;
        }
        const char* bound = firstGiven({{aimShareMin_.has_value(), "--adaptive-aim-share-min"},
                                        {aimShareMax_.has_value(), "--adaptive-aim-share-max"}});
        if (bound && !a.aim.learnShare)
            throw Error(cat(bound, ": applies with --adaptive-aim-share learned (the share is fixed otherwise)"));
        if (const char* o = bound ? bound : (aimShare_ && a.aim.learnShare ? "--adaptive-aim-share learned" : nullptr);
            o && !a.guide.window)
            throw Error(cat(o, ": the share is learned from the weight windows' sums, which ", windowsOff, " turns off"));
        a.aim.shareMin = aimShareMin_.value_or(a.aim.shareMin);
        a.aim.shareMax = aimShareMax_.value_or(a.aim.shareMax);
        a.aim.power = aimPower_.value_or(a.aim.power);
        if (openingsShare_ && *openingsShare_ == "auto") {
            a.openingsAuto = true;
            a.openingsShare = 0.0;
        } else if (openingsShare_) {
            const std::optional<double> v = parseWholeNumber(*openingsShare_);
            if (!v)
                throw Error(cat("--adaptive-openings-share '", printable(*openingsShare_, 40),
                                "': expected auto or a number in [0, 1)"));
            a.openingsAuto = false;
            a.openingsShare = *v;
        }
        if (openingsRacePaths_ && !a.openingsAuto)
            throw Error("--adaptive-openings-race-paths: applies with --adaptive-openings-share auto");
        a.openingsRacePaths = openingsRacePaths_.value_or(a.openingsRacePaths);
        if (!a.aim.enabled)
            a.openingsAuto = false;  // the default, auto: no aim, no panes to start on
        validateAdaptiveOptions(a);
    }

private:
    std::optional<std::string> base_, estimate_, weights_, target_, guide_, guideVertices_, window_, windowVertices_, aim_,
        aimShare_, openingsShare_;
    std::optional<int> initialDepth_, maxDepth_, initialSkyDepth_, maxSkyDepth_, guideVoxels_, guideDepth_, windowSplit_;
    std::optional<double> defensive_, diskShare_, split_, prior_, guideShare_, guideSplit_, guideSpaceSplit_, guideMemory_,
        guideMinGain_, guideMinContributions_,
        windowSurvival_, windowLater_, aimPower_, aimShareMin_, aimShareMax_;
    std::optional<std::uint64_t> firstPass_, openingsRacePaths_;
    std::optional<std::uint32_t> maxCells_;
};

}  // namespace

const char* estimateName(GridEstimate e)
{
    for (const auto& k : kEstimates)
        if (k.estimate == e)
            return k.name;
    return "unknown";
}

const GridEstimate* estimateNamed(const std::string& name)
{
    for (const auto& k : kEstimates)
        if (name == k.name)
            return &k.estimate;
    return nullptr;
}

void validateAdaptiveOptions(const AdaptiveOptions& o)
{
    if (o.base != EmissionMethod::Uniform && o.base != EmissionMethod::Portal)
        throw Error("--base: expected uniform or portal");
    if (o.maxSkyDepth < 0 || o.maxSkyDepth > 12)
        throw Error(cat("--adaptive-max-sky-depth ", o.maxSkyDepth, ": must be in 0..12"));
    if (o.initialSkyDepth < 0 || o.initialSkyDepth > 5 || o.initialSkyDepth > o.maxSkyDepth)
        throw Error(cat("--adaptive-initial-sky-depth ", o.initialSkyDepth, ": must be in 0..5 and at most "
                        "--adaptive-max-sky-depth (", o.maxSkyDepth, ")"));
    if (o.maxDepth < 0 || o.maxDepth > 16)
        throw Error(cat("--adaptive-max-depth ", o.maxDepth, ": must be in 0..16"));
    if (o.initialDepth < 0 || o.initialDepth > 6 || o.initialDepth > o.maxDepth)
        throw Error(cat("--adaptive-initial-depth ", o.initialDepth, ": must be in 0..6 and at most "
                        "--adaptive-max-depth (", o.maxDepth, ")"));
    if (!(o.defensive > 0.0 && o.defensive <= 1.0))
        throw Error(cat("--adaptive-defensive ", o.defensive, ": must be in (0, 1] (a share of 0 "
                        "would let cells that have not shown light yet die: bias)"));
    if (!(o.diskShare > 0.0 && o.diskShare < 1.0))
        throw Error(cat("--adaptive-disk-share ", o.diskShare, ": must be in (0, 1) (with 0, light "
                        "that does not start through a marked portal would be lost)"));
    if (!(o.splitGain > 0.0 && o.splitGain <= 1.0))
        throw Error(cat("--adaptive-split ", o.splitGain, ": must be in (0, 1]"));
    if (o.firstPass < 1024 || o.firstPass > (std::uint64_t{1} << 40))
        throw Error(cat("--adaptive-first-pass ", o.firstPass, ": must be in 1024..2^40 paths"));
    if (!(o.priorPaths > 0.0 && o.priorPaths <= 1e9))
        throw Error(cat("--adaptive-prior ", o.priorPaths, ": must be in (0, 10^9] pseudo-paths"));
    if (o.maxCells < 1 || o.maxCells > (1u << 22))
        throw Error(cat("--adaptive-max-cells ", o.maxCells, ": must be in 1..4194304"));
    if (o.openingsRacePaths < (1u << 16) || o.openingsRacePaths > (std::uint64_t{1} << 40))
        throw Error(cat("--adaptive-openings-race-paths ", o.openingsRacePaths, ": must be in 65536..2^40 paths"));
    if (!(o.openingsShare >= 0.0 && o.openingsShare < 1.0))
        throw Error(cat("--adaptive-openings-share ", o.openingsShare, ": must be in [0, 1) (the light paths keep "
                        "the light the walks cannot take)"));
    validateGuideOptions(o.guide);
    validateOpeningAimOptions(o.aim);
}

std::unique_ptr<StrategyOptionBlock> makeAdaptiveOptionBlock() { return std::make_unique<AdaptiveOptionBlock>(); }

nlohmann::json adaptiveFingerprint(const EmissionSettings& e)
{
    const AdaptiveOptions& a = e.adaptive;
    nlohmann::json j = {{"base", methodName(a.base)},
            {"initial_depth", a.initialDepth},
            {"max_depth", a.maxDepth},
            {"initial_sky_depth", a.initialSkyDepth},
            {"max_sky_depth", a.maxSkyDepth},
            {"estimate", static_cast<int>(a.estimate)},
            {"defensive", a.defensive},
            {"disk_share", a.diskShare},
            {"split_gain", a.splitGain},
            {"prior_paths", a.priorPaths},
            {"weigh_batches", a.weighBatches},
            {"first_pass", a.firstPass},
            {"max_cells", a.maxCells},
            {"guide", a.guide.enabled},
            {"guide_share", a.guide.share},
            {"guide_voxels", a.guide.voxelsAcross},
            {"guide_depth", a.guide.maxDepth},
            {"guide_split", a.guide.splitShare},
            {"guide_space_split", a.guide.spatialSplitConnections},
            {"guide_memory_mib", a.guide.memoryMiB},
            {"guide_every_vertex", a.guide.everyVertex},
            {"window", a.guide.window},
            {"window_rule", static_cast<int>(a.guide.windowRule)},
            {"window_split_max", a.guide.windowSplitMax},
            {"window_min_survival", a.guide.windowMinSurvival},
            {"window_every_vertex", a.guide.windowEveryVertex},
            {"window_later", a.guide.windowLater},
            {"aim", a.aim.enabled},
            {"aim_share", a.aim.cosineShare},
            {"aim_power", a.aim.power}};
    if (a.openingsAuto) {  // absent at 0: a checkpoint written before the option still resumes
        j["openings_share"] = "auto";
        j["openings_race_paths"] = a.openingsRacePaths;
    } else if (a.openingsShare > 0.0) {
        j["openings_share"] = a.openingsShare;
    }
    return j;
}

}  // namespace fen
