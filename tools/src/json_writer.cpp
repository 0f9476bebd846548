// A minimal streaming JSON writer.
#include "json_writer.hpp"

#include <cmath>
#include <cstdio>

namespace hv::tools
{

void JsonWriter::separate()
{
    if (after_key_) {
        after_key_ = false;
        return;
    }
    if (!first_.empty()) {
        if (!first_.back()) {
            out_ += ',';
        }
        first_.back() = false;
    }
}

JsonWriter &JsonWriter::begin_object()
{
    separate();
    out_ += '{';
    first_.push_back(true);
    return *this;
}

JsonWriter &JsonWriter::end_object()
{
    first_.pop_back();
    out_ += '}';
    return *this;
}

JsonWriter &JsonWriter::begin_array()
{
    separate();
    out_ += '[';
    first_.push_back(true);
    return *this;
}

JsonWriter &JsonWriter::end_array()
{
    first_.pop_back();
    out_ += ']';
    return *this;
}

JsonWriter &JsonWriter::key(const std::string &k)
{
    value(k);
    out_ += ':';
    after_key_ = true;
    return *this;
}

JsonWriter &JsonWriter::value(const std::string &s)
{
    separate();
    out_ += '"';
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out_ += '\\';
            out_ += static_cast<char>(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out_ += buf;
        } else {
            out_ += static_cast<char>(c);
        }
    }
    out_ += '"';
    return *this;
}

JsonWriter &JsonWriter::value(double d)
{
    separate();
    if (!std::isfinite(d)) {
        out_ += "null";
        return *this;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", d);
    out_ += buf;
    return *this;
}

JsonWriter &JsonWriter::value(std::int64_t n)
{
    separate();
    out_ += std::to_string(n);
    return *this;
}

JsonWriter &JsonWriter::value(bool b)
{
    separate();
    out_ += b ? "true" : "false";
    return *this;
}

} // namespace hv::tools
