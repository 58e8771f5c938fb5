// kernel_source.h — where kernel sources come from, and `#include` resolution.
//
// Kernels are embedded into the binary at build time (kernels/CMakeLists.txt), so fenestra runs
// from any directory. FEN_KERNEL_DIR=<path to kernels/> reads them from disk instead: edit a
// kernel and rerun, no rebuild. Includes are resolved here, not by the OpenCL compiler, relative
// to kernels/, each file once; `#line` markers keep compiler messages pointing at our own files
// ("kernels/lib/tri_packet.h:42:7: error: ...") on PoCL and NVIDIA alike.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace fen { namespace ocl {

// Generated at build time: (path relative to kernels/, contents).
const std::vector<std::pair<std::string, std::string>>& embeddedKernelFiles();

// Reads one kernel file by its path relative to kernels/; returns false when it does not exist.
using KernelFileReader = std::function<bool(const std::string& path, std::string* contents)>;

// The reader fenestra uses: disk under $FEN_KERNEL_DIR when set, else the embedded files.
KernelFileReader defaultKernelReader();

// `mainFile` with every `#include "..."` expanded once, with #line markers. Throws fen::Error
// naming the including file and line when an include cannot be found.
std::string resolveKernelSource(const std::string& mainFile, const KernelFileReader& reader);

} }  // namespace fen::ocl
