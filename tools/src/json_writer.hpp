// A minimal streaming JSON writer for the tools' machine-readable summaries: objects,
// arrays, strings, integers and finite doubles (non-finite doubles are written as null).
#ifndef HV_TOOLS_JSON_WRITER_HPP
#define HV_TOOLS_JSON_WRITER_HPP

#include <cstdint>
#include <string>
#include <vector>

namespace hv::tools
{

class JsonWriter
{
  public:
    JsonWriter &begin_object();
    JsonWriter &end_object();
    JsonWriter &begin_array();
    JsonWriter &end_array();
    JsonWriter &key(const std::string &k); // inside an object, before each value
    JsonWriter &value(const std::string &s);
    JsonWriter &value(const char *s)
    {
        return value(std::string(s));
    }
    JsonWriter &value(double d);
    JsonWriter &value(std::int64_t n);
    JsonWriter &value(bool b);
    const std::string &str() const
    {
        return out_;
    }

  private:
    void separate();
    std::string out_;
    std::vector<bool> first_; // per open container: no element written yet
    bool after_key_ = false;
};

} // namespace hv::tools

#endif
