// Command-line parsing shared by the tools: "--name value" or "--name=value", numbers
// checked for being whole and finite, and one exit-code convention for every program.
#ifndef HV_TOOLS_CLI_ARGS_HPP
#define HV_TOOLS_CLI_ARGS_HPP

#include <stdexcept>
#include <string>
#include <vector>

namespace hv::tools
{

// Exit codes of every tool (documented in each --help).
enum ExitCode : int {
    kExitOk = 0,
    kExitFailure = 1, // the work itself failed (I/O, a check that did not hold)
    kExitBadInput = 2 // bad command line or bad configuration: nothing was done
};

// A command-line or input problem; what() is the one-line message to print.
class UsageError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// Bad content of an input file; what() already starts with "<path>:<line>: <key>: " and is
// printed as it is (no program-name prefix), like a compiler's message.
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

    bool done() const
    {
        return pos_ >= args_.size();
    }
    // Next option name ("--side"); a "--side=left" form keeps "left" as its pending value.
    std::string next_option();
    // The value of the option just read (from "=value" or the following argument).
    std::string value();
    double value_double();
    long value_long(long min, long max);

  private:
    std::vector<std::string> args_;
    std::size_t pos_ = 0;
    std::string option_;
    std::string pending_;
    bool has_pending_ = false;
};

} // namespace hv::tools

#endif
