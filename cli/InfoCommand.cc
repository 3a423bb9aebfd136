// cloudgraph info FILE: the summary of a primitive-set file (.cgp), fully validated.

#include <cstdio>

#include "cli/Commands.h"
#include "cli/Common.h"
#include "core/Error.h"
#include "formats/PrimitiveFile.h"

namespace cg::cli {

int infoCommand(const Args& args)
{
    OptionParser opts(args, "info");
    return guarded([&] {
        opts.parse();
        if (opts.positionals().size() != 1)
            throw InputError("command line", "usage: cloudgraph info FILE");
        const std::string& file = opts.positionals()[0];
        formats::PrimitiveFileReader reader(file);
        // Read every frame too, so the checksums of the whole file are verified.
        std::uint64_t total = 0;
        for (int s = 0; s < reader.frames(); ++s) {
            reader.readFrame(s);
            total += reader.counts()[static_cast<std::size_t>(s)];
        }
        const float* lo = reader.boundsMin();
        const float* hi = reader.boundsMax();
        std::printf("%s: CloudGraph primitive set, format version %u\n", file.c_str(),
                    formats::kPrimitiveFileVersion);
        std::printf("  frames:      %d (Delta s = %g s, %g s in all)\n", reader.frames(),
                    reader.frameTime(), reader.frameTime() * (reader.frames() - 1));
        std::printf("  units:       metres, relative to the cloud origin\n");
        std::printf("  particles:   N_f(0) = %u, N_f(last) = %u, %llu positions stored\n",
                    reader.counts().front(), reader.counts().back(),
                    static_cast<unsigned long long>(total));
        std::printf("  bounds:      x [%g, %g]  y [%g, %g]  z [%g, %g] m\n", lo[0], hi[0], lo[1],
                    hi[1], lo[2], hi[2]);
        std::printf("  file size:   %llu bytes, checksums ok\n",
                    static_cast<unsigned long long>(reader.fileSize()));
        return kExitOk;
    });
}

}  // namespace cg::cli
