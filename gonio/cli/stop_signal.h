#pragma once
// SIGINT and SIGTERM during a long run: the first asks the run to stop at the next unit boundary
// (it leaves its checkpoint), a second one ends the process at once.
namespace gonio {

void install_stop_handlers();
bool stop_requested();

} // namespace gonio
