#include "apps/number_flags.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"

namespace pt {

long long parse_whole_number(const std::string& flag, const std::string& text, long long lo,
                             long long hi) {
    errno = 0;
    char* end = nullptr;
    long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE || v < lo || v > hi) {
        std::ostringstream s;
        s << flag << ": expected a whole number";
        if (hi == lo) s << " equal to " << lo;
        else if (hi >= (1ll << 30)) s << " >= " << lo;
        else s << " in [" << lo << ", " << hi << "]";
        s << ", got '" << text << "'";
        throw InputError(s.str());
    }
    return v;
}

double parse_real_number(const std::string& flag, const std::string& text, double lo, double hi,
                         bool open_lo) {
    char* end = nullptr;
    double v = std::strtod(text.c_str(), &end);
    bool ok = !text.empty() && *end == '\0' && std::isfinite(v) && (open_lo ? v > lo : v >= lo) &&
              v <= hi;
    if (!ok) {
        std::ostringstream s;
        s << flag << ": expected a number " << (open_lo ? "> " : ">= ") << lo;
        if (hi < 1e300) s << " and <= " << hi;
        s << ", got '" << text << "'";
        throw InputError(s.str());
    }
    return v;
}

}  // namespace pt
