// Qt looks up the runtime folder ($XDG_RUNTIME_DIR) when it starts its GUI part (the
// workstation, and the offscreen platform that the command line's plots, reports and
// their fonts need) and, when the variable is not set (no desktop session: ssh, a
// service, CI), warns on stderr. Both programs' stderr is for their own messages.
#pragma once

namespace palpation::app::cli {

/// Without $XDG_RUNTIME_DIR: names the folder Qt would have used ($TMPDIR or /tmp,
/// "runtime-USER", private to the user), or, when that one is not the user's own, a
/// private folder of its own removed at exit. Call first in main(), before Qt starts.
void set_runtime_dir();

}  // namespace palpation::app::cli
