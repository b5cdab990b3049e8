// `gonio keys [--markdown]`: every config key, from the components' declarations.
#include "gonio/cli/command.h"
#include "gonio/config/config.h"

#include <cstdio>

namespace gonio {

namespace {
std::function<int()> setup(CLI::App& app, const CliContext&) {
    auto markdown = std::make_shared<bool>(false);
    app.add_flag("--markdown", *markdown, "Print the configuration table of docs/configuration.md (Markdown)");
    return [markdown] {
        std::fputs((*markdown ? keys_markdown() : keys_text()).c_str(), stdout);
        return 0;
    };
}
} // namespace

const Command& keys_command() {
    static const Command c{"keys", "List every config key: its section, range, default and meaning",
                           setup};
    return c;
}

} // namespace gonio
