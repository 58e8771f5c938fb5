// batch_cmd.cpp — `fenestra batch` (batch_cmd.h).
#include "batch/batch_cmd.h"

#include <algorithm>
#include <chrono>
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
#include "render/checkpoint.h"
#include "render/render_cmd.h"
#include "render/render_options.h"
#include "util/error.h"
#include "util/fnv.h"

namespace fen {

namespace {

struct Job {
    std::string name;
    std::vector<std::string> args;
};

std::string slurpFile(const std::string& path, const std::string& what)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(cat(printable(path), ": cannot open ", what));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
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

// A job's key: fenestra's build, its arguments, and every file it read, by path and bytes. Empty
// when a file it read is gone.
std::string jobKey(const Job& job, const std::vector<std::string>& inputs)
{
    Fnv f;
    f.text(buildId());
    for (const std::string& a : job.args)
        f.text(a);
    for (const std::string& p : inputs) {
        std::ifstream in(p, std::ios::binary);
        if (!in)
            return "";
        std::ostringstream s;
        s << in.rdbuf();
        f.text(p);
        f.text(s.str());
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
    return hex;
}

// Next to the jobs file: JOBS.state.json, JOBS.summary.json, JOBS.summary.csv.
std::string sidePath(const std::string& jobsPath, const std::string& suffix)
{
    std::string base = jobsPath;
    if (base.size() > 5 && base.substr(base.size() - 5) == ".json")
        base.resize(base.size() - 5);
    return base + suffix;
}

void writeText(const std::string& path, const std::string& text)
{
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!(out << text) || !out.flush())
            throw Error(cat(printable(path), ": cannot write"));
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec)
        throw Error(cat(printable(path), ": cannot write (", ec.message(), ")"));
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
    std::string status;  // done, skipped, failed, stopped
    double seconds = 0.0;
    std::string json, error;
    nlohmann::json figures;  // paths, mean luminance, noise (from the job's JSON output)
};

// One job: parsed as `fenestra render` parses its arguments, run on the shared context.
Outcome runJob(const Job& job, ocl::Context& ctx, std::vector<std::string>* inputs)
{
    Outcome o;
    RenderOptions opt;
    CLI::App app{"fenestra render", "render"};
    addRenderOptions(app, opt);
    std::vector<std::string> args(job.args.rbegin(), job.args.rend());  // CLI11 takes them reversed
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        throw Error(cat(printable(e.what(), 400), " (the arguments of `fenestra render`)"));
    }
    if (!opt.device.empty())
        throw Error("--device: a batch runs every job on its own device (fenestra batch --device)");
    validateRenderOptions(opt);
    RenderHooks hooks;
    hooks.context = &ctx;
    hooks.inputs = inputs;
    hooks.jsonPath = &o.json;
    const int status = runRender(opt, hooks);
    o.status = status == 130 ? "stopped" : "done";
    return o;
}

}  // namespace

int runBatch(const BatchOptions& options)
{
    const std::vector<Job> jobs = readJobs(options.jobsPath);
    const std::string statePath = sidePath(options.jobsPath, ".state.json");
    const std::string summaryJson = sidePath(options.jobsPath, ".summary.json");
    const std::string summaryCsv = sidePath(options.jobsPath, ".summary.csv");
    nlohmann::json state = nlohmann::json::object();
    if (std::filesystem::exists(statePath)) {
        state = nlohmann::json::parse(slurpFile(statePath, "the batch's state"), nullptr, false);
        if (!state.is_object() || !state.contains("jobs") || !state["jobs"].is_object())
            throw Error(cat(printable(statePath), ": not a batch state file (remove it to run every job again)"));
    } else {
        state["jobs"] = nlohmann::json::object();
    }
    ocl::Context ctx(ocl::selectDevice(options.device));
    std::fprintf(stderr, "fenestra: batch %s: %zu jobs on %s\n", printable(options.jobsPath).c_str(), jobs.size(),
                 ctx.info().label().c_str());

    std::vector<Outcome> outcomes;
    int failed = 0;
    bool stopped = false;
    for (std::size_t i = 0; i < jobs.size() && !stopped; ++i) {
        const Job& job = jobs[i];
        const auto t0 = std::chrono::steady_clock::now();
        Outcome o;
        // Skipped: the same build, arguments and input bytes as when it finished, its JSON still there.
        const nlohmann::json* before = state["jobs"].contains(job.name) ? &state["jobs"][job.name] : nullptr;
        if (!options.rerun && before && before->value("status", "") == "done") {
            const std::vector<std::string> inputs = before->value("inputs", std::vector<std::string>{});
            const std::string json = before->value("json", "");
            if (!json.empty() && std::filesystem::exists(json) && jobKey(job, inputs) == before->value("key", "")) {
                o.status = "skipped";
                o.json = json;
            }
        }
        std::fprintf(stderr, "fenestra: batch [%zu/%zu] %s: %s\n", i + 1, jobs.size(), job.name.c_str(),
                     o.status == "skipped" ? "unchanged since it finished, skipped" : "running");
        if (o.status.empty()) {
            std::vector<std::string> inputs;
            try {
                o = runJob(job, ctx, &inputs);
            } catch (const Error& e) {
                o.status = "failed", o.error = e.what();
            } catch (const cl::Error& e) {
                o.status = "failed", o.error = "OpenCL: " + ocl::describe(e);
            } catch (const std::bad_alloc&) {
                o.status = "failed", o.error = "out of host memory";
            }
            o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            if (o.status == "failed") {
                ++failed;
                std::fprintf(stderr, "fenestra: batch [%zu/%zu] %s: failed: %s\n", i + 1, jobs.size(),
                             job.name.c_str(), printable(o.error, 4000).c_str());
                state["jobs"].erase(job.name);
            } else if (o.status == "stopped") {
                stopped = true;
                state["jobs"].erase(job.name);
            } else {
                state["jobs"][job.name] = {{"status", "done"}, {"key", jobKey(job, inputs)}, {"inputs", inputs},
                                           {"json", o.json}};
            }
            makeUtf8(state);
            writeText(statePath, state.dump(1) + "\n");
        }
        if (!o.json.empty() && (o.status == "done" || o.status == "skipped")) {
            const nlohmann::json r = nlohmann::json::parse(slurpFile(o.json, "a job's JSON output"), nullptr, false);
            if (r.is_object())
                o.figures = {{"paths", r.value("paths", 0ull)},
                             {"mean_luminance_cd_m2", r.value("mean_luminance_cd_m2", 0.0)},
                             {"noise_std_err_cd_m2", r.contains("noise_std_err_cd_m2") ? r["noise_std_err_cd_m2"]
                                                                                         : nlohmann::json(nullptr)}};
        }
        outcomes.push_back(o);
    }

    // The summary: every job, run or not.
    nlohmann::json list = nlohmann::json::array();
    std::string csv = "name,status,seconds,paths,mean_luminance_cd_m2,noise_std_err_cd_m2,json,error\n";
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        const Outcome o = i < outcomes.size() ? outcomes[i] : Outcome{"not run", 0.0, "", "", nullptr};
        nlohmann::json e = {{"name", jobs[i].name}, {"status", o.status}, {"seconds", o.seconds},
                            {"json", o.json.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.json)},
                            {"error", o.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.error)}};
        std::string paths, mean, noise;
        if (o.figures.is_object()) {
            e.update(o.figures);
            paths = std::to_string(o.figures["paths"].get<unsigned long long>());
            mean = number(o.figures["mean_luminance_cd_m2"].get<double>());
            if (o.figures["noise_std_err_cd_m2"].is_number())
                noise = number(o.figures["noise_std_err_cd_m2"].get<double>());
        }
        list.push_back(e);
        csv += cat(csvField(jobs[i].name), ",", o.status, ",", number(o.seconds), ",", paths, ",", mean, ",", noise,
                   ",", csvField(o.json), ",", csvField(o.error), "\n");
    }
    nlohmann::json summary{{"jobs_file", options.jobsPath}, {"failed", failed}, {"jobs", list}};
    makeUtf8(summary);
    writeText(summaryJson, summary.dump(1) + "\n");
    writeText(summaryCsv, csv);
    std::fprintf(stderr, "fenestra: batch: %zu jobs, %d failed%s; summary in %s and %s\n", jobs.size(), failed,
                 stopped ? ", stopped by a signal" : "", printable(summaryJson).c_str(), printable(summaryCsv).c_str());
    if (stopped)
        return 130;
    if (failed > 0)
        throw Error(cat("batch ", printable(options.jobsPath), ": ", failed, " of ", jobs.size(), " jobs failed (", printable(summaryCsv), ")"));
    return 0;
}

}  // namespace fen
