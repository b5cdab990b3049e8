#include "gonio/cli/commands.h"
#include "gonio/config/config.h"

#include <cstdio>

namespace gonio {

int run_keys_command(bool markdown) {
    std::fputs((markdown ? keys_markdown() : keys_text()).c_str(), stdout);
    return 0;
}

} // namespace gonio
