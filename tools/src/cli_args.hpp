// Command-line parsing shared by the tools: "--name value" or "--name=value", numbers
// checked for being whole and finite. Exit codes: hv/exit_codes.h (docs/EXIT_CODES.md).
#ifndef HV_TOOLS_CLI_ARGS_HPP
#define HV_TOOLS_CLI_ARGS_HPP

#include <stdexcept>
#include <string>
#include <vector>

namespace hv::tools
{

// A command-line or input problem; what() is the one-line message to print after
// "PROGRAM: " ("--side: expected left, right or both, got 'up'").
class UsageError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// Bad content of an input file; what() starts with "<path>:<line>: <key>: ".
class InputError : public UsageError
{
  public:
    using UsageError::UsageError;
};

// Walks argv; each accessor throws UsageError naming the option on bad input.
class ArgReader
{
  public:
    ArgReader(int argc, char **argv);

    // True after the last argument; throws UsageError when that was "--flag=value" of a
    // flag that takes no value.
    bool done() const;
    // Next option name ("--side"); a "--side=left" form keeps "left" as its pending value.
    std::string next_option();
    // The value of the option just read (from "=value" or the following argument).
    std::string value();
    double value_double();
    long value_long(long min, long max);

  private:
    void check_no_pending() const;

    std::vector<std::string> args_;
    std::size_t pos_ = 0;
    std::string option_;
    std::string pending_;
    bool has_pending_ = false;
};

} // namespace hv::tools

#endif
