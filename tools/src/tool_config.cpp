// Loading the harvest configuration for a tool, and the side names of the command line.
#include "tool_config.hpp"

#include <climits>
#include <unistd.h>

#include "cli_args.hpp"
#include "hv/file_io.h"

namespace hv::tools
{

std::string default_config_path()
{
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        std::string bin(exe, static_cast<size_t>(n));
        bin = bin.substr(0, bin.find_last_of('/')); // PREFIX/bin
        std::string installed = bin.substr(0, bin.find_last_of('/')) + "/share/harvest/harvest.cfg";
        if (access(installed.c_str(), R_OK) == 0)
            return installed;
    }
    return "config/harvest.cfg";
}

hv_config_t load_config(const std::string &path)
{
    hv_config_t cfg;
    char err[512] = {0};
    if (hv_config_load(path.c_str(), &cfg, err, sizeof err) != HV_OK) {
        throw InputError(err[0] != '\0' ? std::string(err) : path + ": cannot be loaded");
    }
    return cfg;
}

std::vector<hv_side_t> parse_sides(const std::string &option, const std::string &value)
{
    if (value == "left") {
        return {HV_SIDE_LEFT};
    }
    if (value == "right") {
        return {HV_SIDE_RIGHT};
    }
    if (value == "both") {
        return {HV_SIDE_LEFT, HV_SIDE_RIGHT};
    }
    throw UsageError(option + ": expected left, right or both, got '" + value + "'");
}

const char *side_name(hv_side_t side)
{
    return side == HV_SIDE_LEFT ? "left" : "right";
}

} // namespace hv::tools
