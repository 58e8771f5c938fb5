// checkpoint.cpp — writing, checking and reading checkpoints (checkpoint.h).
#include "render/checkpoint.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/json_text.h"
#include "io/output_files.h"
#include "util/error.h"
#include "util/fnv.h"

namespace fen {

namespace {

constexpr const char* kMagic = "FENESTRA CHECKPOINT 1\n";
constexpr std::uint64_t kMaxBytes = std::uint64_t{8} << 30;  // a 16k x 16k image's sums fit

std::string le64(std::uint64_t v)
{
    std::string s(8, '\0');
    for (int i = 0; i < 8; ++i)
        s[i] = static_cast<char>((v >> (8 * i)) & 0xffu);
    return s;
}

std::uint64_t fromLe64(const std::string& s, std::size_t at)
{
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
        v |= static_cast<std::uint64_t>(static_cast<unsigned char>(s[at + i])) << (8 * i);
    return v;
}

// The first key (a.b.c) where the two fingerprints differ, with both values.
bool firstDifference(const nlohmann::json& want, const nlohmann::json& have, const std::string& at,
                     std::string* where)
{
    if (want.is_object() && have.is_object()) {
        for (const auto& [k, v] : want.items()) {
            const std::string key = at.empty() ? k : at + "." + k;
            if (!have.contains(k)) {
                *where = cat(key, " is missing from it");
                return true;
            }
            if (firstDifference(v, have[k], key, where))
                return true;
        }
        for (const auto& [k, v] : have.items())
            if (!want.contains(k)) {
                *where = cat(at.empty() ? k : at + "." + k, " is not a setting of this render");
                return true;
            }
        return false;
    }
    if (want == have)
        return false;
    *where = cat(at, " was ", printable(dumpUtf8(have), 80), ", not ", printable(dumpUtf8(want), 80));
    return true;
}

}  // namespace

std::string buildId()
{
    static const std::string id = [] {  // the executable does not change while it runs
        Fnv f;
        std::ifstream exe("/proc/self/exe", std::ios::binary);
        char buf[1 << 16];
        bool any = false;
        while (exe.read(buf, sizeof buf) || exe.gcount() > 0) {
            f.add(buf, static_cast<std::size_t>(exe.gcount()));
            any = true;
        }
        return any ? cat("fenestra 0.1 build ", hex64(f.h)) : std::string("fenestra 0.1");
    }();
    return id;
}

namespace {

// Geometry, materials, textures, texture coordinates, node names and portal marks: what a
// DeviceScene holds (and the portals, which a render also reads from the scene).
Fnv geometryFnv(const Scene& s)
{
    Fnv f;
    f.value(s.triangles.size());
    if (!s.triangles.empty())
        f.add(s.triangles.data(), s.triangles.size() * sizeof(Triangle));
    f.value(s.triangleMaterial.size());
    if (!s.triangleMaterial.empty())
        f.add(s.triangleMaterial.data(), s.triangleMaterial.size() * sizeof(std::uint32_t));
    f.value(s.triangleNode.size());
    if (!s.triangleNode.empty())
        f.add(s.triangleNode.data(), s.triangleNode.size() * sizeof(std::uint32_t));
    for (const Material& m : s.materials) {
        f.value(m.albedo);
        f.value(m.glass);
        f.value(m.transmission);
        f.value(m.ior);
        if (m.texture >= 0) {  // only then: an untextured scene hashes as before textures existed
            f.value(m.texture);
            f.value(m.texCoord);
        }
    }
    for (const Texture& t : s.textures) {
        f.value(t.width);
        f.value(t.height);
        f.value(static_cast<int>(t.wrapS) | static_cast<int>(t.wrapT) << 2 | int{t.nearest} << 4);
        f.add(t.rgb.data(), t.rgb.size());
    }
    if (!s.triangleUv.empty())
        f.add(s.triangleUv.data(), s.triangleUv.size() * sizeof(s.triangleUv[0]));
    for (std::size_t i = 0; i < s.nodeNames.size(); ++i) {
        f.text(s.nodeNames[i]);
        f.value(i < s.nodePortal.size() ? static_cast<int>(s.nodePortal[i]) : -1);
    }
    return f;
}

}  // namespace

std::uint64_t geometryHash(const Scene& s)
{
    return geometryFnv(s).h;
}

std::uint64_t sceneHash(const Scene& s)
{
    Fnv f = geometryFnv(s);  // then the light: the same sequence of values as one pass over both
    f.value(s.sun.present);
    f.value(s.sun.travelDirection);
    f.value(s.sun.illuminanceRgb_lux);
    f.value(s.sun.angularRadiusRad);
    f.value(static_cast<int>(s.sky.type));
    f.value(s.sky.luminance_cd_m2);
    f.value(s.sky.cieType);
    f.value(s.sky.zenithLuminance_cd_m2);
    f.value(s.sky.sunAltitudeDeg);
    f.value(s.sky.sunAzimuthDeg);
    for (double v : s.sky.zenithDeg)
        f.value(v);
    for (double v : s.sky.azimuthDeg)
        f.value(v);
    for (const auto& row : s.sky.table_cd_m2)
        for (double v : row)
            f.value(v);
    if (s.sky.type == SkySpec::Type::Perez) {
        f.value(s.sky.perezEpsilon);
        f.value(s.sky.perezDelta);
        f.value(s.sky.diffuseHorizontal_lux);
    }
    if (s.sky.groundAlbedo != 0.0)  // only then: a scene without a ground hashes as before grounds existed
        f.value(s.sky.groundAlbedo);
    return f.h;
}

void writeCheckpoint(const std::string& path, const nlohmann::json& fingerprint, const std::string& payload)
{
    const nlohmann::json header = {{"build", buildId()}, {"fingerprint", fingerprint}};
    std::string bytes = kMagic;
    bytes += dumpUtf8(header) + "\n";
    bytes += le64(payload.size());
    bytes += payload;
    Fnv f;
    f.add(bytes.data(), bytes.size());
    bytes += le64(f.h);
    OutputFiles out;
    out.add(path, std::move(bytes));
    out.commit();
}

std::string readCheckpoint(const std::string& path, const nlohmann::json& fingerprint)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(cat(path, ": cannot open the checkpoint: ", std::strerror(errno)));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0 || static_cast<std::uint64_t>(size) > kMaxBytes)
        throw Error(cat(path, ": not a checkpoint (unreadable, or larger than 8 GiB)"));
    in.seekg(0);
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (!in.read(bytes.data(), size))
        throw Error(cat(path, ": cannot read the checkpoint"));
    return checkpointPayload(bytes, path, fingerprint);
}

std::string checkpointPayload(const std::string& bytes, const std::string& path, const nlohmann::json& fingerprint)
{
    const std::size_t magic = std::strlen(kMagic);
    if (bytes.compare(0, magic, kMagic) != 0)
        throw Error(cat(path, ": not a fenestra checkpoint"));
    const std::size_t eol = bytes.find('\n', magic);
    if (eol == std::string::npos || bytes.size() - eol - 1 < 16)
        throw Error(cat(path, ": the checkpoint is truncated"));
    Fnv f;
    f.add(bytes.data(), bytes.size() - 8);
    if (f.h != fromLe64(bytes, bytes.size() - 8))
        throw Error(cat(path, ": the checkpoint is damaged (checksum mismatch): truncated or altered"));
    const std::uint64_t length = fromLe64(bytes, eol + 1);
    if (length != bytes.size() - eol - 1 - 16)
        throw Error(cat(path, ": the checkpoint is damaged (its length does not match the file)"));
    const nlohmann::json header = nlohmann::json::parse(bytes.begin() + magic, bytes.begin() + eol, nullptr, false);
    if (header.is_discarded() || !header.is_object() || !header.contains("build") || !header.contains("fingerprint") ||
        !header["build"].is_string())
        throw Error(cat(path, ": the checkpoint's header is not valid"));
    const std::string build = header["build"], mine = buildId();
    if (build != mine)
        throw Error(cat(path, ": made by ", printable(build, 80), ", not by this ", mine,
                        ": a checkpoint is resumed by the build that wrote it"));
    const nlohmann::json& theirs = header["fingerprint"];
    if (fingerprint.contains("scene") && theirs.is_object() && theirs.contains("scene") &&
        theirs["scene"] != fingerprint["scene"])
        throw Error(cat(path, ": made for another render: the scene differs (content hash ",
                        printable(dumpUtf8(theirs["scene"]), 40), ", not ", printable(dumpUtf8(fingerprint["scene"]), 40), ")"));
    std::string where;
    if (firstDifference(fingerprint, theirs, "", &where))
        throw Error(cat(path, ": made for another render: ", where));
    return bytes.substr(eol + 1 + 8, static_cast<std::size_t>(length));
}

void requireCheckpointTarget(const std::string& path, const std::string& option)
{
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) {
        if (errno == ENOENT)
            return;
        throw Error(cat(option, " ", printable(path), ": ", std::strerror(errno)));
    }
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        throw Error(cat(option, " ", printable(path), ": exists and is not a regular file; a checkpoint is written "
                                                       "only over a checkpoint"));
    const std::size_t magic = std::strlen(kMagic);
    std::string head(magic, '\0');
    std::ifstream in(path, std::ios::binary);
    if (!in.read(head.data(), static_cast<std::streamsize>(magic)) || head != kMagic)
        throw Error(cat(option, " ", printable(path), ": exists and is not a fenestra checkpoint; a checkpoint is "
                                                       "written only over a checkpoint or to a new file"));
}

void writeLoopState(StateWriter& w, const LoopState& l)
{
    w.u64("loop.base", l.base);
    w.u64("loop.per_batch", l.perBatch);
    w.u64("loop.done", static_cast<std::uint64_t>(l.done));
    w.f64("loop.render_seconds", l.renderSeconds);
    w.f64("loop.calibration_seconds", l.calibrationSeconds);
    const BatchCounts& n = l.counts;
    w.u64s("loop.counts", {n.extensionRays, n.shadowRays, n.cameraRays, n.badContributions, n.overflows,
                           n.statsOverflows, n.maxBounceCuts, n.cameraGlassCuts, n.diffuseVertices,
                           n.guidedVertices, n.splitBranches, n.windowCulls, n.openingWalks, n.openingWalkRays});
    w.f64("loop.cut_flux", n.cutFlux);
}

void readLoopState(StateReader& in, const LoopRules& rules, LoopState* out)
{
    LoopState l;
    l.base = in.u64("loop.base");
    l.perBatch = in.u64("loop.per_batch");
    l.done = static_cast<int>(in.u64("loop.done", static_cast<std::uint64_t>(rules.batches)));
    l.renderSeconds = in.f64("loop.render_seconds");
    l.calibrationSeconds = in.f64("loop.calibration_seconds");
    // 14 counters; 12 in a checkpoint written before the openings' walks (their two then 0)
    const std::vector<std::uint64_t> c = in.u64s("loop.counts", 14);
    if (c.size() != 12 && c.size() != 14)
        in.fail("loop.counts", "neither 14 counters nor the 12 of a checkpoint before the openings' walks");
    BatchCounts& n = l.counts;
    n.extensionRays = c[0], n.shadowRays = c[1], n.cameraRays = c[2], n.badContributions = c[3];
    n.overflows = c[4], n.statsOverflows = c[5], n.maxBounceCuts = c[6], n.cameraGlassCuts = c[7];
    n.diffuseVertices = c[8], n.guidedVertices = c[9], n.splitBranches = c[10], n.windowCulls = c[11];
    if (c.size() == 14)
        n.openingWalks = c[12], n.openingWalkRays = c[13];
    if (n.guidedVertices > n.diffuseVertices)
        in.fail("loop.counts", "more guided vertices than diffuse ones");
    n.cutFlux = in.f64("loop.cut_flux");
    const std::uint64_t batches = static_cast<std::uint64_t>(rules.batches);
    if (l.perBatch == 0)
        in.fail("loop.per_batch", "zero");
    if (rules.paths > 0 && l.perBatch != std::max<std::uint64_t>(1, rules.paths / batches))
        in.fail("loop.per_batch", cat(l.perBatch, " paths, not the ", rules.paths / batches,
                                      " of --paths over --batches"));
    if (l.perBatch > static_cast<std::uint64_t>(1e15))
        in.fail("loop.per_batch", "more paths than a render can trace");
    if (l.done < 0 || (rules.paths > 0 && l.done > rules.batches))
        in.fail("loop.done", cat(l.done, " batches of ", rules.batches));
    std::uint64_t counted = 0;
    if (__builtin_mul_overflow(l.perBatch, static_cast<std::uint64_t>(l.done), &counted) || l.base < counted ||
        (rules.paths > 0 && l.base != counted))
        in.fail("loop.base", "does not match the batches done");
    if (l.renderSeconds < 0.0 || l.calibrationSeconds < 0.0 || n.cutFlux < 0.0)
        in.fail("loop.render_seconds", "a negative time or flux");
    *out = l;
}

}  // namespace fen
