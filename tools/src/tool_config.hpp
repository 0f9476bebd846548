// Loading the harvest configuration for a tool, and the side names of the command line.
#ifndef HV_TOOLS_TOOL_CONFIG_HPP
#define HV_TOOLS_TOOL_CONFIG_HPP

#include <string>
#include <vector>

#include "hv/config.h"

namespace hv::tools
{

// The config used when --config is not given: PREFIX/share/harvest/harvest.cfg beside the
// running program (PREFIX/bin/<tool>, found from /proc/self/exe, so a moved prefix still
// works) when that file exists, else config/harvest.cfg of the current folder (the source
// tree's root, where the build's programs are run from).
std::string default_config_path();

// Load and validate `path`. Throws InputError with the core's one-line message
// "<path>:<line>: <key>: <message>" (or "<path>: open: ..." when unreadable).
hv_config_t load_config(const std::string &path);

// "left" | "right" | "both" -> the sides, in the order left, right. Throws UsageError
// naming `option` otherwise.
std::vector<hv_side_t> parse_sides(const std::string &option, const std::string &value);

const char *side_name(hv_side_t side);

} // namespace hv::tools

#endif
