// Command-line parsing shared by the tools.
#include "cli_args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace hv::tools
{

ArgReader::ArgReader(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        args_.emplace_back(argv[i]);
    }
}

void ArgReader::check_no_pending() const
{
    if (has_pending_) {
        throw UsageError(option_ + "=" + pending_ + ": takes no value (see --help)");
    }
}

bool ArgReader::done() const
{
    check_no_pending();
    return pos_ >= args_.size();
}

std::string ArgReader::next_option()
{
    check_no_pending();
    std::string a = args_.at(pos_++);
    if (a.size() < 2 || a.compare(0, 2, "--") != 0) {
        throw UsageError(a + ": unexpected argument (options start with --; see --help)");
    }
    std::size_t eq = a.find('=');
    if (eq != std::string::npos) {
        pending_ = a.substr(eq + 1);
        has_pending_ = true;
        a.resize(eq);
    }
    option_ = a;
    return a;
}

std::string ArgReader::value()
{
    if (has_pending_) {
        has_pending_ = false;
        return pending_;
    }
    if (pos_ >= args_.size()) {
        throw UsageError(option_ + ": needs a value (see --help)");
    }
    return args_[pos_++];
}

double ArgReader::value_double()
{
    std::string v = value();
    char *end = nullptr;
    errno = 0;
    double d = std::strtod(v.c_str(), &end);
    if (v.empty() || end == v.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(d)) {
        throw UsageError(option_ + ": '" + v + "' is not a finite number");
    }
    return d;
}

long ArgReader::value_long(long min, long max)
{
    std::string v = value();
    char *end = nullptr;
    errno = 0;
    long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || errno == ERANGE) {
        throw UsageError(option_ + ": '" + v + "' is not an integer");
    }
    if (n < min || n > max) {
        throw UsageError(option_ + ": " + v + " outside [" + std::to_string(min) + ", " +
                         std::to_string(max) + "]");
    }
    return n;
}

} // namespace hv::tools
