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
// Fault injection for tests: FEN_FAIL_WRITE=<text> makes writing any output whose name contains
// <text> fail as a full disk would (ENOSPC).
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

// The folder of `path` exists or is created, `path` is not a folder, and a file can be created
// there (an exclusive temporary, removed at once); else fen::Error naming `what` and the path.
void checkOutputPath(const std::string& path, const std::string& what);

// A PNG, in memory (the EXR encoder is io/exr_io.h's encodeExr).
std::string encodePng(int width, int height, int channels, const std::vector<unsigned char>& pixels);

}  // namespace fen
