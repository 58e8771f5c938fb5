// kernel_source.cpp — embedded/disk kernel files and the include resolver (kernel_source.h).
#include "cl/kernel_source.h"

#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <unordered_map>

#include "util/error.h"

namespace fen { namespace ocl {

KernelFileReader defaultKernelReader()
{
    if (const char* dir = std::getenv("FEN_KERNEL_DIR"); dir && *dir) {
        const std::string root = dir;
        return [root](const std::string& path, std::string* contents) {
            std::ifstream f(root + "/" + path, std::ios::binary);
            if (!f)
                return false;
            std::ostringstream s;
            s << f.rdbuf();
            *contents = s.str();
            return true;
        };
    }
    return [](const std::string& path, std::string* contents) {
        static const std::unordered_map<std::string, const std::string*> index = [] {
            std::unordered_map<std::string, const std::string*> m;
            for (const auto& [name, text] : embeddedKernelFiles())
                m.emplace(name, &text);
            return m;
        }();
        const auto it = index.find(path);
        if (it == index.end())
            return false;
        *contents = *it->second;
        return true;
    };
}

namespace {

void expand(const std::string& path, const std::string& text, const KernelFileReader& reader,
            std::set<std::string>& seen, std::string& out)
{
    static const std::regex includeLine(R"(^\s*#\s*include\s*([<"])([^">]+)[">].*$)");
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    out += cat("#line 1 \"kernels/", path, "\"\n");
    while (std::getline(in, line)) {
        ++lineNo;
        std::smatch m;
        if (!std::regex_match(line, m, includeLine)) {
            out += line;
            out += '\n';
            continue;
        }
        const std::string target = m[2].str();
        if (m[1].str() == "<") {
            // Left to the compiler: the shared headers include <cstdint> etc. only in their
            // host branch, which the OpenCL preprocessor skips.
            out += line;
            out += '\n';
            continue;
        }
        if (seen.count(target)) {
            out += '\n';  // each file once (this also breaks include cycles); keep the line count
            continue;
        }
        std::string contents;
        if (!reader(target, &contents))
            throw Error(cat("kernels/", path, ":", lineNo, ": cannot find included file \"",
                            target, "\""));
        seen.insert(target);
        expand(target, contents, reader, seen, out);
        out += cat("#line ", lineNo + 1, " \"kernels/", path, "\"\n");
    }
}

}  // namespace

std::string resolveKernelSource(const std::string& mainFile, const KernelFileReader& reader)
{
    std::string text;
    if (!reader(mainFile, &text))
        throw Error(cat("kernel source kernels/", mainFile, " not found",
                        std::getenv("FEN_KERNEL_DIR") ? " under FEN_KERNEL_DIR" : ""));
    std::set<std::string> seen{mainFile};
    // No contraction into fused multiply-adds anywhere: the triangle test needs it off to be
    // watertight (lib/tri_packet.h), and every function must round the same in every program it
    // is part of -- the wavefront stages and the fused kernel (lib/fused_kernel.h) give
    // bit-identical images only if they do. OpenCL C has no build option for this, so every
    // program starts with the pragma.
    std::string out = "#pragma OPENCL FP_CONTRACT OFF\n";
    expand(mainFile, text, reader, seen, out);
    return out;
}

} }  // namespace fen::ocl
