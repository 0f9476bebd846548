// A progress line on stderr for long work: rewritten in place on a terminal, one line per
// tenth of the work otherwise (so logs stay short). Thread-safe to call from one thread.
#ifndef HV_TOOLS_PROGRESS_HPP
#define HV_TOOLS_PROGRESS_HPP

#include <chrono>
#include <cstddef>
#include <string>

namespace hv::tools
{

class Progress
{
  public:
    Progress(std::string label, std::size_t total, bool quiet);
    void update(std::size_t done);
    void finish();

  private:
    std::string label_;
    std::size_t total_;
    bool quiet_;
    bool tty_;
    int last_decile_ = -1;
    std::chrono::steady_clock::time_point start_, last_print_;
};

} // namespace hv::tools

#endif
