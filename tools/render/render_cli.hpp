// lantern-render: renders a scene file's GI frame (../shared/SCENES.md, docs/scenes.md).
#pragma once

namespace lantern::tools {

// Runs the CLI. Exit status: 0 success, 1 runtime failure (no Vulkan device, cannot write),
// 2 bad input (arguments, scene file, --set). On any failure no output file is written.
int render_main(int argc, char** argv);

} // namespace lantern::tools
