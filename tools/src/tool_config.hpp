// Loading the harvest configuration for a tool, and the side names of the command line.
#ifndef HV_TOOLS_TOOL_CONFIG_HPP
#define HV_TOOLS_TOOL_CONFIG_HPP

#include <string>
#include <vector>

#include "hv/config.h"

namespace hv::tools
{

// Load and validate `path`. Throws InputError with the core's one-line message
// "<path>:<line>: <key>: <message>" (or "<path>: open: ..." when unreadable).
hv_config_t load_config(const std::string &path);

// "left" | "right" | "both" -> the sides, in the order left, right. Throws UsageError
// naming `option` otherwise.
std::vector<hv_side_t> parse_sides(const std::string &option, const std::string &value);

const char *side_name(hv_side_t side);

} // namespace hv::tools

#endif
