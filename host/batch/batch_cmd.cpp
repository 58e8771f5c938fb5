// batch_cmd.cpp — `fenestra batch` (batch_cmd.h).
#include "batch/batch_cmd.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cl/cl_error.h"
#include "cl/context.h"
#include "cl/device.h"
#include "io/json_text.h"
#include "io/output_files.h"
#include "render/checkpoint.h"
#include "render/device_scene.h"
#include "render/render_cmd.h"
#include "render/render_options.h"
#include "util/error.h"
#include "util/fnv.h"
#include "team/team.h"
#include "util/stop_signals.h"

namespace fen {

namespace {

struct Job {
    std::string name;
    std::vector<std::string> args;
};

// A file's bytes into *out; false when it cannot be read.
bool readBytes(const std::string& path, std::string* out)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return false;
    std::ostringstream s;
    s << in.rdbuf();
    *out = s.str();
    return true;
}

std::string slurpFile(const std::string& path, const std::string& what)
{
    std::string bytes;
    if (!readBytes(path, &bytes))
        throw Error(cat(printable(path), ": cannot open ", what));
    return bytes;
}

// The jobs file, checked whole before anything runs: one-line errors naming the file and key.
std::vector<Job> readJobs(const std::string& path)
{
    const std::string text = slurpFile(path, "the jobs file");
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded())
        throw Error(cat(printable(path), ": not JSON (expected {\"jobs\": [{\"name\": ..., \"render\": [...]}, ...]})"));
    if (!j.is_object())
        throw Error(cat(printable(path), ": expected an object with a \"jobs\" array"));
    for (const auto& [key, value] : j.items())
        if (key != "jobs")
            throw Error(cat(printable(path), ": unknown key '", printable(key, 60), "' (a jobs file has \"jobs\")"));
    if (!j.contains("jobs") || !j["jobs"].is_array() || j["jobs"].empty())
        throw Error(cat(printable(path), ": \"jobs\" must be a non-empty array"));
    std::vector<Job> jobs;
    std::set<std::string> names;
    for (std::size_t i = 0; i < j["jobs"].size(); ++i) {
        const nlohmann::json& e = j["jobs"][i];
        const std::string where = cat(printable(path), ": jobs[", i, "]");
        if (!e.is_object())
            throw Error(cat(where, ": expected an object {\"name\": ..., \"render\": [...]}"));
        for (const auto& [key, value] : e.items())
            if (key != "name" && key != "render")
                throw Error(cat(where, ": unknown key '", printable(key, 60), "' (a job has \"name\" and \"render\")"));
        if (!e.contains("name") || !e["name"].is_string())
            throw Error(cat(where, ".name: a string is required"));
        Job job;
        job.name = e["name"].get<std::string>();
        const bool nameOk = !job.name.empty() && job.name.size() <= 100 &&
                            std::all_of(job.name.begin(), job.name.end(), [](char c) {
                                return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
                            });
        if (!nameOk)
            throw Error(cat(where, ".name '", printable(job.name, 60), "': 1 to 100 of the characters A-Z a-z 0-9 - _ ."));
        if (!names.insert(job.name).second)
            throw Error(cat(where, ".name '", job.name, "': another job has this name"));
        if (!e.contains("render") || !e["render"].is_array() || e["render"].empty())
            throw Error(cat(where, ".render: the arguments of `fenestra render` as an array of strings"));
        for (std::size_t k = 0; k < e["render"].size(); ++k) {
            if (!e["render"][k].is_string())
                throw Error(cat(where, ".render[", k, "]: a string is required"));
            job.args.push_back(e["render"][k].get<std::string>());
        }
        jobs.push_back(std::move(job));
    }
    return jobs;
}

// A job's key: fenestra's build, the device asked for, the kernel environment, the job's arguments,
// and every file it read, by path and bytes. Empty (matching nothing) when a file it read is gone.
std::string jobKey(const Job& job, const std::string& device, const std::vector<std::string>& inputs)
{
    Fnv f;
    f.text(buildId());
    f.text(device);
    for (const char* env : {"FEN_KERNEL_DIR", "FEN_LOCAL_SIZE"}) {
        const char* v = std::getenv(env);
        f.text(v ? v : "");
    }
    for (const std::string& a : job.args)
        f.text(a);
    for (const std::string& p : inputs) {
        std::string bytes;
        if (!readBytes(p, &bytes))
            return "";
        f.text(p);
        f.text(bytes);
    }
    return hex64(f.h);
}

// A state entry that says the job finished: {"status": "done", "key": K, "inputs": [...], "json": P}.
// Anything else (an older or edited file) says nothing: the job runs.
bool finishedEntry(const nlohmann::json& e, std::string* key, std::vector<std::string>* inputs, std::string* json)
{
    if (!e.is_object() || e.value("status", nlohmann::json()) != "done" || !e.contains("key") || !e["key"].is_string() ||
        !e.contains("json") || !e["json"].is_string() || !e.contains("inputs") || !e["inputs"].is_array())
        return false;
    for (const auto& i : e["inputs"]) {
        if (!i.is_string())
            return false;
        inputs->push_back(i.get<std::string>());
    }
    *key = e["key"].get<std::string>();
    *json = e["json"].get<std::string>();
    return !key->empty();
}

// Next to the jobs file: JOBS.state.json, JOBS.summary.json, JOBS.summary.csv.
std::string sidePath(const std::string& jobsPath, const std::string& suffix)
{
    std::string base = jobsPath;
    if (base.size() > 5 && base.substr(base.size() - 5) == ".json")
        base.resize(base.size() - 5);
    return base + suffix;
}

// Written as a render's outputs are (io/output_files.h): a unique temporary, then a rename.
void writeText(const std::string& path, const std::string& text)
{
    OutputFiles out;
    out.add(path, text);
    out.commit();
}

std::string number(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

std::string csvField(const std::string& s)
{
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string out = "\"";
    for (const char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

struct Outcome {
    std::string status;  // done, skipped, failed, stopped, not run
    double seconds = 0.0;
    std::string json, error;
    nlohmann::json figures;  // paths, mean luminance, noise (from the job's JSON output)
    std::vector<std::string> inputs;  // the files it read
};

// What the summary shows of a job, from its JSON output: paths, the image's mean luminance and
// noise (null with --no-image), and each sensor's mean illuminance with its standard error, least
// and greatest cell and uniformity. Null when the output is not a render's JSON.
nlohmann::json jobFigures(const nlohmann::json& r)
{
    if (!r.is_object() || !r.contains("paths") || !r["paths"].is_number_unsigned())
        return nullptr;
    const auto numberOrNull = [](const nlohmann::json& o, const char* key) {
        return o.is_object() && o.contains(key) && o[key].is_number() ? o[key] : nlohmann::json(nullptr);
    };
    const bool image = !(r.contains("image") && r["image"] == false);  // --no-image: sensors alone
    nlohmann::json f = {{"paths", r["paths"]},
                        {"mean_luminance_cd_m2", image ? numberOrNull(r, "mean_luminance_cd_m2") : nullptr},
                        {"noise_std_err_cd_m2", image ? numberOrNull(r, "noise_std_err_cd_m2") : nullptr},
                        {"sensors", nlohmann::json::object()}};
    if (r.contains("sensors") && r["sensors"].is_object())
        for (const auto& [name, e] : r["sensors"].items()) {
            nlohmann::json t = nlohmann::json::object();
            for (const char* key : {"mean_lux", "mean_lux_std_err", "min_lux", "max_lux", "uniformity"})
                t[key] = numberOrNull(e, key);
            f["sensors"][name] = t;
        }
    // an annual study's headline figures
    if (r.contains("annual") && r["annual"].is_object()) {
        nlohmann::json a = nlohmann::json::object();
        for (const char* key : {"sda_pct", "ase_pct", "mean_da_pct", "mean_udi_useful_pct", "mean_lux"})
            a[key] = numberOrNull(r["annual"], key);
        f["annual"] = a;
    }
    return f;
}

// A job's line in the batch's state: a finished job with what makes it finished (its key, inputs
// and JSON), for a rerun to skip; anything else, no line (the job runs again).
void recordState(nlohmann::json& state, const std::string& name, const Outcome& o, const std::string& key)
{
    if (o.status == "done")
        state["jobs"][name] = {{"status", "done"}, {"key", key}, {"inputs", o.inputs}, {"json", o.json}};
    else
        state["jobs"].erase(name);
    makeUtf8(state);
}

// One job: parsed as `fenestra render` parses its arguments, run on the shared context. Its key is
// taken from its inputs as they were read, before it renders (a file edited meanwhile makes the
// next run run it again).
Outcome runJob(const Job& job, ocl::Context& ctx, DeviceSceneCache& scenes, const std::string& device,
               std::string* key)
{
    Outcome o;
    RenderOptions opt;
    CLI::App app{"fenestra render", "render"};
    addRenderOptions(app, opt);
    std::vector<std::string> args(job.args.rbegin(), job.args.rend());  // CLI11 takes them reversed
    try {
        app.parse(args);
    } catch (const CLI::CallForHelp&) {
        throw Error("--help: a job renders; see fenestra render --help");
    } catch (const CLI::ParseError& e) {
        throw Error(cat(printable(e.what(), 400), " (the arguments of `fenestra render`)"));
    }
    if (!opt.device.empty())
        throw Error("--device: a batch runs every job on its own device (fenestra batch --device)");
    validateRenderOptions(opt);
    RenderHooks hooks;
    hooks.team = &soloTeam();  // a job is one rank's, also under mpirun
    hooks.context = &ctx;
    hooks.sceneCache = &scenes;
    hooks.onInputs = [&](const std::vector<std::string>& inputs, const std::string& json) {
        o.inputs = inputs;
        o.json = json;
        *key = jobKey(job, device, inputs);
    };
    const int status = runRender(opt, hooks);
    o.status = status == 130 ? "stopped" : "done";
    return o;
}

// A state file's {"jobs": {...}}, `what` naming it in an error.
nlohmann::json readStateFile(const std::string& path, const char* what)
{
    nlohmann::json s = nlohmann::json::parse(slurpFile(path, what), nullptr, false);
    if (!s.is_object() || !s.contains("jobs") || !s["jobs"].is_object())
        throw Error(cat(printable(path), ": not a batch state file (remove it to run every job again)"));
    return s;
}

// Under mpirun each rank records the jobs it finishes in a shard of its own beside the state
// (JOBS.state.rankK.json), as they finish; rank 0 folds them into the state at the end. A batch
// killed before then leaves its shards, which the next run folds in first: nothing finished is lost.
std::string shardPath(const std::string& statePath, int rank)
{
    return statePath.substr(0, statePath.size() - 5) + ".rank" + std::to_string(rank) + ".json";
}

// The shards beside `statePath`, in name order.
std::vector<std::string> shardsOf(const std::string& statePath)
{
    const std::filesystem::path p(statePath);
    const std::string prefix = p.filename().string().substr(0, p.filename().string().size() - 5) + ".rank";
    std::vector<std::string> found;
    std::error_code ec;
    const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.size() > prefix.size() + 5 && name.compare(0, prefix.size(), prefix) == 0 &&
            name.compare(name.size() - 5, 5, ".json") == 0)
            found.push_back(e.path().string());
    }
    std::sort(found.begin(), found.end());
    return found;
}

// The state: the file (none: no job finished), with the shards a killed batch under mpirun left
// folded in (a shard's null entry: the job ran again and did not finish); written back and the
// shards removed when there were any.
nlohmann::json readState(const std::string& statePath)
{
    nlohmann::json state = {{"jobs", nlohmann::json::object()}};
    if (std::filesystem::exists(statePath))
        state = readStateFile(statePath, "the batch's state");
    // entries are checked where they are read (finishedEntry): one that is not what a batch
    // writes only makes its job run
    const std::vector<std::string> shards = shardsOf(statePath);
    for (const std::string& shard : shards) {
        const nlohmann::json s = readStateFile(shard, "a rank's batch state");
        for (const auto& [name, entry] : s["jobs"].items()) {
            if (entry.is_null())
                state["jobs"].erase(name);
            else
                state["jobs"][name] = entry;
        }
    }
    if (!shards.empty()) {
        writeText(statePath, state.dump(1) + "\n");
        std::error_code ec;  // one left behind is folded in again next time: harmless
        for (const std::string& shard : shards)
            std::filesystem::remove(shard, ec);
    }
    return state;
}

}  // namespace

int runBatch(const BatchOptions& options)
{
    const std::vector<Job> jobs = readJobs(options.jobsPath);
    const std::string statePath = sidePath(options.jobsPath, ".state.json");
    const std::string summaryJson = sidePath(options.jobsPath, ".summary.json");
    const std::string summaryCsv = sidePath(options.jobsPath, ".summary.csv");
    // Under mpirun the ranks take the jobs as they come free (a shared ticket counter), each job
    // on one rank's device; each records what it finishes in its shard, and rank 0 gathers the
    // outcomes at the end and writes the state and summaries.
    Team& team = processTeam();
    const bool spread = team.size() > 1;
    nlohmann::json state;
    if (team.root())
        state = readState(statePath);
    if (spread) {  // rank 0's reading, shards folded in, for everyone
        std::string text = state.dump();
        team.broadcast(text);
        state = nlohmann::json::parse(text);
    }
    nlohmann::json shard = {{"jobs", nlohmann::json::object()}};
    const StopSignals signals;  // one for the whole batch: a stop between jobs is seen too
    auto ctx = std::make_unique<ocl::Context>(ocl::selectDevice(options.device, team.localRank()));
    DeviceSceneCache scenes;  // a scene's BVH and buffers, kept while its jobs follow one another
    const std::string rankTag = spread ? cat(" (rank ", team.rank(), ")") : "";
    std::fprintf(stderr, "fenestra: batch %s: %zu jobs on %s%s\n", printable(options.jobsPath).c_str(), jobs.size(),
                 ctx->info().label().c_str(), rankTag.c_str());

    std::vector<Outcome> outcomes(jobs.size());
    std::vector<std::string> keys(jobs.size());  // of the jobs done here, for the state
    for (Outcome& o : outcomes)
        o.status = "not run";
    int failed = 0;
    bool stopped = false;
    std::uint64_t sequence = 0;
    for (;;) {
        if ((stopped = StopSignals::requested()))
            break;
        const std::uint64_t ticket = spread ? team.ticket() : sequence++;
        if (ticket >= jobs.size())
            break;
        const std::size_t i = static_cast<std::size_t>(ticket);
        const Job& job = jobs[i];
        const auto t0 = std::chrono::steady_clock::now();
        Outcome o;
        // Skipped: the same build, device, arguments and input bytes as when it finished, its JSON there.
        std::string key, json;
        std::vector<std::string> inputs;
        if (!options.rerun && state["jobs"].contains(job.name) &&
            finishedEntry(state["jobs"][job.name], &key, &inputs, &json) && std::filesystem::exists(json) &&
            jobKey(job, options.device, inputs) == key) {
            o.status = "skipped";
            o.json = json;
        }
        std::fprintf(stderr, "fenestra: batch [%zu/%zu] %s: %s%s\n", i + 1, jobs.size(), job.name.c_str(),
                     o.status == "skipped" ? "unchanged since it finished, skipped" : "running", rankTag.c_str());
        if (o.status.empty()) {
            key.clear();
            try {
                o = runJob(job, *ctx, scenes, options.device, &key);
            } catch (const Error& e) {
                o.status = "failed", o.error = e.what();
            } catch (const cl::Error& e) {
                o.status = "failed", o.error = "OpenCL: " + ocl::describe(e);
                // A device error can leave the queue unusable: the next job gets a new context
                // (and the scene cache, whose buffers were the old context's, starts again).
                try {
                    scenes = DeviceSceneCache();
                    ctx = std::make_unique<ocl::Context>(ocl::selectDevice(options.device));
                } catch (const std::exception&) {
                }
            } catch (const std::bad_alloc&) {
                o.status = "failed", o.error = "out of host memory";
            } catch (const std::exception& e) {
                o.status = "failed", o.error = e.what();
            }
            o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (o.status == "failed") {
                ++failed;
                std::fprintf(stderr, "fenestra: batch [%zu/%zu] %s: failed: %s\n", i + 1, jobs.size(),
                             job.name.c_str(), printable(o.error, 4000).c_str());
            }
            keys[i] = key;
            if (!spread) {
                recordState(state, job.name, o, key);
                writeText(statePath, state.dump(1) + "\n");
            } else {  // this rank's shard; rank 0 writes the state once it has every rank's outcomes
                recordState(shard, job.name, o, key);
                if (o.status != "done")
                    shard["jobs"][job.name] = nullptr;  // not finished: the state must forget it
                writeText(shardPath(statePath, team.rank()), shard.dump(1) + "\n");
            }
        }
        if (!o.json.empty() && (o.status == "done" || o.status == "skipped" || o.status == "stopped")) {
            std::string text;
            if (readBytes(o.json, &text))
                o.figures = jobFigures(nlohmann::json::parse(text, nullptr, false));
        }
        outcomes[i] = o;
        if (o.status == "stopped")
            stopped = true;
    }
    if (spread) {
        // every rank's outcomes to rank 0, which alone goes on to write
        nlohmann::json mine = nlohmann::json::array();
        for (std::size_t i = 0; i < jobs.size(); ++i)
            if (outcomes[i].status != "not run")
                mine.push_back({{"job", i}, {"status", outcomes[i].status}, {"seconds", outcomes[i].seconds},
                                {"json", outcomes[i].json}, {"error", outcomes[i].error},
                                {"inputs", outcomes[i].inputs}, {"key", keys[i]}, {"figures", outcomes[i].figures}});
        makeUtf8(mine);
        const std::vector<std::string> all = team.gatherToRoot(mine.dump());
        stopped = anyMember(team, stopped);
        markLastCollectiveDone();
        if (!team.root())
            return stopped ? 130 : 0;
        failed = 0;
        for (const std::string& text : all)
            for (const nlohmann::json& e : nlohmann::json::parse(text)) {
                const std::size_t i = e["job"].get<std::size_t>();
                Outcome& o = outcomes[i];
                o.status = e["status"];
                o.seconds = e["seconds"];
                o.json = e["json"];
                o.error = e["error"];
                o.inputs = e["inputs"].get<std::vector<std::string>>();
                o.figures = e["figures"];
                failed += o.status == "failed" ? 1 : 0;
                if (o.status != "skipped")
                    recordState(state, jobs[i].name, o, e["key"]);
            }
        writeText(statePath, state.dump(1) + "\n");
        std::error_code ec;
        for (int k = 0; k < team.size(); ++k)  // folded in: the shards go
            std::filesystem::remove(shardPath(statePath, k), ec);
    }

    // The summary: every job, run or not.
    nlohmann::json list = nlohmann::json::array();
    std::string csv =
        "name,status,seconds,paths,mean_luminance_cd_m2,noise_std_err_cd_m2,sensors_mean_lux,sda_pct,ase_pct,json,error\n";
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        const Outcome& o = outcomes[i];
        nlohmann::json e = {{"name", jobs[i].name}, {"status", o.status}, {"seconds", o.seconds},
                            {"json", o.json.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.json)},
                            {"error", o.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.error)}};
        std::string paths, mean, noise, sensorMeans, sda, ase;
        if (o.figures.is_object()) {
            e.update(o.figures);
            paths = std::to_string(o.figures["paths"].get<unsigned long long>());
            if (o.figures["mean_luminance_cd_m2"].is_number())
                mean = number(o.figures["mean_luminance_cd_m2"].get<double>());
            if (o.figures["noise_std_err_cd_m2"].is_number())
                noise = number(o.figures["noise_std_err_cd_m2"].get<double>());
            // each sensor's mean illuminance, NAME=LUX separated by ';'
            for (const auto& [name, t] : o.figures["sensors"].items())
                if (t["mean_lux"].is_number())
                    sensorMeans += (sensorMeans.empty() ? "" : ";") + name + "=" + number(t["mean_lux"].get<double>());
            if (o.figures.contains("annual")) {
                const nlohmann::json& a = o.figures["annual"];
                if (a["sda_pct"].is_number())
                    sda = number(a["sda_pct"].get<double>());
                if (a["ase_pct"].is_number())
                    ase = number(a["ase_pct"].get<double>());
            }
        }
        list.push_back(e);
        csv += cat(csvField(jobs[i].name), ",", o.status, ",", number(o.seconds), ",", paths, ",", mean, ",", noise, ",",
                   csvField(sensorMeans), ",", sda, ",", ase, ",", csvField(o.json), ",", csvField(o.error), "\n");
    }
    nlohmann::json summary{{"jobs_file", options.jobsPath}, {"failed", failed}, {"jobs", list}};
    makeUtf8(summary);
    OutputFiles out;  // the two summaries, committed as one set
    out.add(summaryCsv, csv);
    out.add(summaryJson, summary.dump(1) + "\n");
    out.commit();
    std::fprintf(stderr, "fenestra: batch: %zu jobs, %d failed%s; summary in %s and %s\n", jobs.size(), failed,
                 stopped ? ", stopped by a signal" : "", printable(summaryJson).c_str(), printable(summaryCsv).c_str());
    if (stopped)
        return 130;
    if (failed > 0)
        throw Error(cat("batch ", printable(options.jobsPath), ": ", failed, " of ", jobs.size(), " jobs failed (", printable(summaryCsv), ")"));
    return 0;
}

}  // namespace fen
