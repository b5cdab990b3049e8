#include "gonio/cli/commands.h"
#include "gonio/export/export.h"

#include <cstdio>

namespace gonio {

int run_export_command(const ExportOptions& options) {
    try {
        const ExportReport r = export_result(options);
        if (!options.quiet) {
            std::printf("%s: %s, %.1f MB in %.2f s\n", r.output.c_str(), options.format.c_str(),
                        r.bytes / 1e6, r.seconds);
            for (const std::string& note : r.notes) std::printf("  %s\n", note.c_str());
        }
        return 0;
    } catch (const ExportRefused& e) {
        std::fprintf(stderr, "gonio export: refused: %s\n", e.what());
        return 3;
    }
}

} // namespace gonio
