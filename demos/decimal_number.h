#pragma once
// A number as a user types it on a command line (--dt, --tolerance, a scene's
// --param value, --grab and --compare entries): decimal only, as JSON writes
// numbers, so that what is read is what is meant. strtod alone also takes
// hexadecimal ("0x1p-8", "0x10"), and reads "1e-3000" as 0 and "1e999" as
// infinity, which the range checks would then report as "got 0" or "got inf".
#include <string>

namespace scenes {

// [+-] digits [. digits] [e [+-] digits] (or [+-] . digits ...), or the words
// nan, inf and infinity (any case; the range checks name them). Throws
// std::invalid_argument without a name ("expected a decimal number, got
// '0x10'"; "'1e-3000' is too small for a double: it would read as 0";
// "'1e999' is too large for a double (above 1.8e+308)").
double readDecimalNumber(const std::string& text);

}  // namespace scenes
