#include "gonio/cli/command.h"

namespace gonio {

const std::vector<const Command*>& commands() {
    static const std::vector<const Command*> all = {
        &model_command(),   &surface_command(), &run_command(),    &merge_command(),
        &ndf_command(),     &compare_command(), &info_command(),   &keys_command(),
        &export_command(),  &cache_command(),   &render_command(), &report_command(),
        &masking_command(), &fit_command()};
    return all;
}

} // namespace gonio
