// opening_aim.cpp — openings from the scene's glass, and the aim learned from what entered by them
// (opening_aim.h; DESIGN.md §3.5).
#include "scatter/opening_aim.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>

#include "io/state_io.h"
#include "scene/scene.h"
#include "util/error.h"
#include "util/fixed_point.h"

namespace fen {

void validateOpeningAimOptions(const OpeningAimOptions& o)
{
    if (!(o.cosineShare > 0.0 && o.cosineShare < 1.0))
        throw Error(cat("--adaptive-aim-share ", o.cosineShare,
                        ": must be in (0, 1) (the cosine keeps every direction drawable; 1 would aim at nothing)"));
    if (!(o.minEntries >= 1.0 && o.minEntries <= 1e12))
        throw Error(cat("--adaptive-aim-min-entries ", o.minEntries, ": must be in 1..10^12"));
    if (!(o.minShare >= 0.0 && o.minShare < 1.0))
        throw Error(cat("--adaptive-aim-min-share ", o.minShare, ": must be in [0, 1)"));
    if (!(o.shareMin > 0.0 && o.shareMin < 1.0))
        throw Error(cat("--adaptive-aim-share-min ", o.shareMin, ": must be in (0, 1)"));
    if (!(o.shareMax >= o.shareMin && o.shareMax <= 1.0))
        throw Error(cat("--adaptive-aim-share-max ", o.shareMax, ": must be in [", o.shareMin,
                        ", 1] (not below --adaptive-aim-share-min)"));
    if (!(o.power > 0.0 && o.power <= 2.0))
        throw Error(cat("--adaptive-aim-power ", o.power, ": must be in (0, 2]"));
}

namespace {

glm::dvec3 triangleCross(const Triangle& t)
{
    return glm::cross(glm::dvec3(t.p1) - glm::dvec3(t.p0), glm::dvec3(t.p2) - glm::dvec3(t.p0));
}

// Union-find over glass triangles.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

}  // namespace

std::vector<Opening> findOpenings(const Scene& scene)
{
    std::vector<std::uint32_t> glass;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i)
        if (scene.materials.at(scene.triangleMaterial.at(i)).glass && glm::length(triangleCross(scene.triangles[i])) > 0.0)
            glass.push_back(static_cast<std::uint32_t>(i));
    std::vector<glm::dvec3> normal(glass.size());
    for (std::size_t k = 0; k < glass.size(); ++k)
        normal[k] = glm::normalize(triangleCross(scene.triangles[glass[k]]));
    // Two glass triangles are one pane when they share a corner (exactly: one mesh's shared vertex)
    // and lie in one plane: normals parallel, each one's corner on the other's plane, within
    // rounding of a float scene (1e-4 of the larger's size).
    auto coplanar = [&](std::size_t a, std::size_t b) {
        if (std::abs(glm::dot(normal[a], normal[b])) < 1.0 - 1e-6)
            return false;
        const Triangle& ta = scene.triangles[glass[a]];
        const Triangle& tb = scene.triangles[glass[b]];
        const double size = std::max(glm::length(glm::dvec3(ta.p1) - glm::dvec3(ta.p0)),
                                     glm::length(glm::dvec3(tb.p1) - glm::dvec3(tb.p0)));
        for (const glm::vec3& p : {tb.p0, tb.p1, tb.p2})
            if (std::abs(glm::dot(normal[a], glm::dvec3(p) - glm::dvec3(ta.p0))) > 1e-4 * size)
                return false;
        return true;
    };
    std::vector<std::size_t> parent(glass.size());
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    std::map<std::array<float, 3>, std::vector<std::size_t>> byCorner;
    for (std::size_t k = 0; k < glass.size(); ++k) {
        const Triangle& t = scene.triangles[glass[k]];
        for (const glm::vec3& p : {t.p0, t.p1, t.p2}) {
            std::vector<std::size_t>& seen = byCorner[{p.x, p.y, p.z}];
            for (std::size_t other : seen)
                if (root(parent, other) != root(parent, k) && coplanar(other, k))
                    parent[root(parent, k)] = root(parent, other);
            seen.push_back(k);
        }
    }
    std::map<std::size_t, std::size_t> paneOf;  // root -> opening, in order of first triangle
    std::vector<Opening> out;
    for (std::size_t k = 0; k < glass.size(); ++k) {
        const std::size_t r = root(parent, k);
        auto [it, fresh] = paneOf.emplace(r, out.size());
        if (fresh) {
            out.emplace_back();
            out.back().normal = normal[k];
        }
        Opening& o = out[it->second];
        o.triangles.push_back(glass[k]);
        o.flipped.push_back(glm::dot(normal[k], o.normal) < 0.0 ? 1 : 0);
        o.area_m2 += 0.5 * glm::length(triangleCross(scene.triangles[glass[k]]));
    }
    std::stable_sort(out.begin(), out.end(), [](const Opening& a, const Opening& b) { return a.area_m2 > b.area_m2; });
    return out;
}

OpeningAim::OpeningAim(ocl::Context& ctx, const OpeningAimOptions& o, const Scene* scene) : ctx_(ctx), opt_(o)
{
    validateOpeningAimOptions(o);
    if (o.enabled && scene) {
        openings_ = findOpenings(*scene);
        if (openings_.size() > FEN_OPENING_MAX) {
            ignoredOpenings_ = openings_.size() - FEN_OPENING_MAX;
            openings_.resize(FEN_OPENING_MAX);  // the largest; paths entering by the rest count as other glass
        }
    }
    std::vector<std::array<std::uint32_t, 2>> pairs;  // (primitive, 2 j + flipped), sorted by primitive
    for (std::size_t j = 0; j < openings_.size(); ++j) {
        const Opening& op = openings_[j];
        firstTriangle_.push_back(triangles_.size());
        for (std::size_t k = 0; k < op.triangles.size(); ++k) {
            pairs.push_back({op.triangles[k], static_cast<std::uint32_t>(2 * j) + static_cast<std::uint32_t>(op.flipped[k])});
            const Triangle& t = scene->triangles[op.triangles[k]];
            const glm::vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
            const glm::dvec3 cr = glm::cross(glm::dvec3(e1), glm::dvec3(e2));  // of the float edges the device gets
            const glm::vec3 nt = glm::vec3(glm::normalize(cr));
            dev::AimTriangle a{};
            a.p0 = {t.p0.x, t.p0.y, t.p0.z, static_cast<float>(0.5 * glm::length(cr))};
            a.e1 = {e1.x, e1.y, e1.z, 0.0f};
            a.e2 = {e2.x, e2.y, e2.z, 0.0f};
            a.normal = {nt.x, nt.y, nt.z, dev::fen_as_float(op.triangles[k])};
            triangles_.push_back(a);
        }
    }
    firstTriangle_.push_back(triangles_.size());
    std::sort(pairs.begin(), pairs.end());
    totals_.assign(openings_.size(), {});
    weight_.assign(openings_.size(), {0.0, 0.0});
    host_.prims = static_cast<std::uint32_t>(pairs.size());
    host_.cosine_share = host_.first_share = static_cast<float>(opt_.cosineShare);
    aim_ = ctx_.buffer(CL_MEM_READ_ONLY, sizeof(dev::OpeningAim), "opening aim", &host_);
    if (pairs.empty())
        pairs.push_back({0u, 0u});  // a placeholder: prims = 0, never read
    prims_ = ctx_.buffer(CL_MEM_READ_ONLY, pairs.size() * 8, "opening primitives", pairs.data());
    stats_ = ctx_.buffer(CL_MEM_READ_WRITE, statWords() * 8, "opening statistics");
    deviceBytes_ = sizeof(dev::OpeningAim) + pairs.size() * 8 + statWords() * 8;
    clearStats();
}

std::size_t OpeningAim::statWords() const
{
    return std::max<std::size_t>(2 * openings_.size(), 1) * FEN_OPENING_STATS_WORDS;
}

void OpeningAim::clearStats()
{
    ctx_.queue().enqueueFillBuffer(stats_, cl_ulong(0), 0, statWords() * 8);
}

// One first vertex's scatter is one sample of s cos + (1 - s) aim. Where the aim's part of the
// density is the larger (its region) the density is about (1 - s) the aim's, elsewhere about s the
// cosine's, so a pass's second moments of what paths leaving in the two regions deliver are about
// A / (1 - s) and B / s, A and B their moments under the aim and the cosine alone: each pass's sums
// times the share that drew them estimate A and B. A / (1 - s) + B / s is least at
// s = sqrt(B) / (sqrt(A) + sqrt(B)). The contributions are summed one by one, not per path, as the
// weight windows' moments are: each lands in its own pixel.
void OpeningAim::learnShare(double mixed, double aimed)
{
    if (!opt_.enabled || !opt_.learnShare || !(mixed > 0.0))
        return;
    const double s = host_.first_share;
    shareA_ += std::min(aimed, mixed) * (1.0 - s);
    shareB_ += std::max(mixed - aimed, 0.0) * s;
    setShare();
}

void OpeningAim::setShare()
{
    if (!(shareA_ + shareB_ > 0.0))
        return;
    const double a = std::sqrt(shareA_), b = std::sqrt(shareB_);
    host_.first_share = static_cast<float>(std::clamp(b / (a + b), opt_.shareMin, opt_.shareMax));
}

void OpeningAim::learn()
{
    if (openings_.empty())
        return;
    const auto t0 = std::chrono::steady_clock::now();
    raw_.resize(2 * openings_.size() * FEN_OPENING_STATS_WORDS);
    ctx_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, raw_.size() * 8, raw_.data());
    for (std::size_t j = 0; j < openings_.size(); ++j)
        for (std::size_t s = 0; s < 2; ++s) {
            const std::uint64_t* w = raw_.data() + (2 * j + s) * FEN_OPENING_STATS_WORDS;
            SideTotals& t = totals_[j][s];
            t.delivered += fixed128(w + FEN_OPENING_DELIVERED_LO);
            t.entered += fixed128(w + FEN_OPENING_ENTERED_LO);
            t.entries += static_cast<double>(w[FEN_OPENING_ENTRIES]);
        }
    clearStats();
    ++passes_;
    rebuild();
    upload();
    learnSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Each side's weight: what a unit of weight entering brings to the image, once minEntries paths
// entered there; aimed at while its weight times its area is minShare of the largest's or more.
// The aim takes the openings with the largest such products first, whole, while FEN_AIM_MAX_TRIS
// triangles last (the rest skipped, reported).
void OpeningAim::rebuild()
{
    const std::size_t n = openings_.size();
    std::vector<std::array<double, 2>> ratio(n, {0.0, 0.0});
    double largest = 0.0, largestRatio = 0.0;
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t s = 0; s < 2; ++s) {
            const SideTotals& t = totals_[j][s];
            if (t.entries >= opt_.minEntries && t.entered > 0.0 && t.delivered > 0.0) {
                ratio[j][s] = t.delivered / t.entered;
                largest = std::max(largest, ratio[j][s] * openings_[j].area_m2);
                largestRatio = std::max(largestRatio, ratio[j][s]);
            }
        }
    std::vector<double> rank(n, 0.0);
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t s = 0; s < 2; ++s) {
            const double product = ratio[j][s] * openings_[j].area_m2;
            const bool aimed = largest > 0.0 && product > 0.0 && product >= opt_.minShare * largest;
            weight_[j][s] = aimed ? std::pow(ratio[j][s] / largestRatio, opt_.power) : 0.0;
            if (aimed)
                rank[j] = std::max(rank[j], product);
        }
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rank[a] > rank[b]; });
    std::uint32_t count = 0;
    aimedOpenings_ = skippedOpenings_ = 0;
    for (std::size_t j : order) {
        if (!(rank[j] > 0.0))
            break;
        const Opening& op = openings_[j];
        if (count + op.triangles.size() > FEN_AIM_MAX_TRIS) {
            ++skippedOpenings_;
            continue;
        }
        ++aimedOpenings_;
        for (std::size_t k = 0; k < op.triangles.size(); ++k) {
            // the triangle's front (where its own normal points) is the pane's side 0 unless flipped
            const std::size_t front = op.flipped[k] ? 1 : 0;
            dev::AimTriangle& t = host_.tri[count++];
            t = triangles_[firstTriangle_[j] + k];
            t.e1.w = static_cast<float>(weight_[j][front]);
            t.e2.w = static_cast<float>(weight_[j][1 - front]);
        }
    }
    host_.triangles = count;
}

void OpeningAim::upload()
{
    ctx_.queue().enqueueWriteBuffer(aim_, CL_TRUE, 0, sizeof(dev::OpeningAim), &host_);
}

void OpeningAim::save(StateWriter& w) const
{
    std::vector<double> v;
    for (const auto& sides : totals_)
        for (const SideTotals& t : sides)
            v.insert(v.end(), {t.delivered, t.entered, t.entries});
    w.f64s("aim.totals", v);
    w.u64("aim.passes", static_cast<std::uint64_t>(passes_));
    w.f64s("aim.share", {shareA_, shareB_});
}

void OpeningAim::load(StateReader& r)
{
    const std::vector<double> v = r.f64s("aim.totals", 6 * openings_.size(), true);
    for (std::size_t j = 0; j < openings_.size(); ++j)
        for (std::size_t s = 0; s < 2; ++s) {
            SideTotals& t = totals_[j][s];
            const double* x = v.data() + 6 * j + 3 * s;
            t.delivered = r.finite("aim.totals", x[0]);
            t.entered = r.finite("aim.totals", x[1]);
            t.entries = r.finite("aim.totals", x[2]);
            if (t.delivered < 0.0 || t.entered < 0.0 || t.entries < 0.0)
                r.fail("aim.totals", "a negative total");
        }
    passes_ = static_cast<int>(r.u64("aim.passes", 1u << 30));
    const std::vector<double> share = r.f64s("aim.share", 2, true);
    shareA_ = r.finite("aim.share", share[0]);
    shareB_ = r.finite("aim.share", share[1]);
    if (shareA_ < 0.0 || shareB_ < 0.0)
        r.fail("aim.share", "a negative second moment");
    host_.first_share = static_cast<float>(opt_.cosineShare);
    if (opt_.learnShare)
        setShare();
    clearStats();
    rebuild();
    upload();
}

nlohmann::json OpeningAim::report() const
{
    nlohmann::json aimed = nlohmann::json::array();
    double entries = 0.0;
    for (std::size_t j = 0; j < openings_.size(); ++j) {
        for (std::size_t s = 0; s < 2; ++s) {
            entries += totals_[j][s].entries;
            if (weight_[j][s] > 0.0)
                aimed.push_back({{"opening", j},
                                 {"side", s},
                                 {"first_triangle", openings_[j].triangles.front()},
                                 {"area_m2", openings_[j].area_m2},
                                 {"weight", weight_[j][s]},
                                 {"entries", totals_[j][s].entries}});
        }
    }
    return {{"enabled", opt_.enabled},
            {"cosine_share", host_.cosine_share},
            {"first_share", host_.first_share},
            {"share_learned", opt_.learnShare},
            {"share_moments", {shareA_, shareB_}},
            {"power", opt_.power},
            {"openings", openings_.size()},
            {"openings_not_learned", ignoredOpenings_},
            {"aimed_openings", aimedOpenings_},
            {"openings_without_room", skippedOpenings_},
            {"aimed_triangles", host_.triangles},
            {"paths_entered", entries},
            {"passes", passes_},
            {"learn_seconds", learnSeconds_},
            {"device_bytes", deviceBytes_},
            {"aimed", aimed}};
}

}  // namespace fen
