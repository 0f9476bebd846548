// Progress line on stderr.
#include "progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace hv::tools
{

Progress::Progress(std::string label, std::size_t total, bool quiet)
    : label_(std::move(label)), total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_print_(start_)
{
}

void Progress::update(std::size_t done)
{
    if (quiet_ || total_ == 0) {
        return;
    }
    auto now = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double>(now - start_).count();
    double pct = 100.0 * static_cast<double>(done) / static_cast<double>(total_);
    if (tty_) {
        if (now - last_print_ < std::chrono::milliseconds(200) && done < total_) {
            return;
        }
        last_print_ = now;
        std::fprintf(stderr, "\r%s: %zu/%zu (%5.1f %%) %.1f s", label_.c_str(), done, total_, pct,
                     elapsed);
        std::fflush(stderr);
        return;
    }
    int decile = static_cast<int>(10 * done / total_);
    if (decile > last_decile_) {
        last_decile_ = decile;
        std::fprintf(stderr, "%s: %zu/%zu (%5.1f %%) %.1f s\n", label_.c_str(), done, total_, pct,
                     elapsed);
    }
}

void Progress::finish()
{
    update(total_);
    if (!quiet_ && tty_) {
        std::fputc('\n', stderr);
    }
}

} // namespace hv::tools
