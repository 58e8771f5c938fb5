// output_files.h — a render's outputs (EXR, noise EXR, PNG previews, JSON) written so that nothing
// is lost and nothing half-written is left where a reader looks.
//
// Every file is encoded in memory first, then written to a new, uniquely named temporary file in
// its own folder (O_EXCL: no existing name is touched), every write and the flush and fsync
// checked; only when all of them are on disk are they renamed over their final names, the JSON
// last. A reader sees the previous render's set, or the new one (the renames are atomic each,
// and the JSON, which names the others, arrives last). On any failure -- a full disk, a removed
// folder -- the temporaries are removed and fen::Error names the file; the previous outputs stay.
// checkOutputPath() proves a folder writable the same way, before a long render.
// The set is committed as a unit: before the first rename a journal (.NAME.commit beside the first
// file, itself written to a temporary and renamed) lists every temporary and its final name; after
// the last it is removed. A process killed between the renames leaves the journal, and the next
// OutputSetLock on that set finishes the renames (every file of the new set, none of the old)
// before anything else. OutputSetLock also serialises renders into one set: an exclusive lock
// (flock on .NAME.lock) held for the render's life, a second render refused at once; holding it,
// temporaries a killed process left behind (".NAME.XXXXXX" beside each file) are removed.
// Fault injection for tests: FEN_FAIL_WRITE=<text> makes writing any output whose name contains
// <text> fail as a full disk would (ENOSPC); FEN_KILL_AFTER_RENAMES=N kills the process (SIGKILL)
// after N renames of a commit.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/image.h"

namespace fen {

class OutputFiles {
public:
    void add(const std::string& path, std::string bytes);
    // Writes all, then renames all into place; throws fen::Error (and leaves the old files) on failure.
    void commit();

private:
    std::vector<std::pair<std::string, std::string>> files_;
};

// The lock on an output set (the files render_cmd writes for one --out), its crash recovery and
// its orphan removal; see above. `files`: every name the set may have, the first the primary.
class OutputSetLock {
public:
    explicit OutputSetLock(const std::vector<std::string>& files);
    ~OutputSetLock();
    OutputSetLock(const OutputSetLock&) = delete;
    OutputSetLock& operator=(const OutputSetLock&) = delete;
    // What the lock found and did: "" or a sentence for the user (a commit finished, orphans removed).
    const std::string& recovered() const { return recovered_; }

private:
    int fd_ = -1;
    std::string lockPath_, recovered_;
};

// The folder of `path` exists or is created, `path` is not a folder, and a file can be created
// there (an exclusive temporary, removed at once); else fen::Error naming `what` and the path.
void checkOutputPath(const std::string& path, const std::string& what);

// A PNG, in memory (the EXR encoder is io/exr_io.h's encodeExr).
std::string encodePng(int width, int height, int channels, const std::vector<unsigned char>& pixels);

}  // namespace fen
