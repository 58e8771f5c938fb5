// batch_cmd.h — `fenestra batch JOBS.json`: many renders in one process (DESIGN.md §4 "Batches").
//
// The jobs file is JSON, each job a name and the arguments of `fenestra render` exactly as typed
// after `render` (paths relative to the directory the batch runs in, as on the command line):
//   {"jobs": [{"name": "noon", "render": ["scenes/room.gltf", "--paths", "2e6", "--out", "out/noon.exr"]},
//             {"name": "june-13h", "render": ["scenes/room.gltf", "--weather", "w.epw", "--weather-hour",
//                                            "06-21:13", "--time", "30", "--out", "out/june.exr"]}]}
// Jobs run in order on one OpenCL context (the device is chosen once, with the batch's --device;
// PoCL's kernel cache is shared as it always is); each gets the options, checks and outputs that
// `fenestra render` with its arguments would, so a job's images are the same bytes either way.
// A job that fails (bad arguments, a missing file, a device error: the next job then gets a new
// context) is reported with its one-line reason and the others go on. Finished jobs are skipped on a
// rerun: JOBS.state.json keeps, per job, a key hashed from fenestra's build, the device asked for,
// the kernel environment, the job's arguments and the bytes of every file it read (as it read them,
// before rendering), and a job whose key is unchanged and whose JSON output is still there is not
// run again (--rerun runs all). JOBS.summary.json and JOBS.summary.csv list every job: status
// (done, skipped, failed, stopped, not run), seconds, paths, mean luminance, noise, each sensor's
// mean illuminance, its JSON output and the error. A stop signal, held for the whole batch (util/stop_signals.h), stops the job in
// flight as `fenestra render` stops (outputs written) and runs no further job.
// Exit status: 0 when no job failed, 1 when any did (after all ran), 130 when stopped.
#pragma once

#include <string>

namespace fen {

struct BatchOptions {
    std::string jobsPath;
    std::string device;  // as `fenestra render --device`: index or name substring
    bool rerun = false;  // run every job, finished or not
};

int runBatch(const BatchOptions& options);

}  // namespace fen
