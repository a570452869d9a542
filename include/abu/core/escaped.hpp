// Text as a terminal line or a CSV comment line may carry it (every layer's messages).
#pragma once

#include <string>
#include <string_view>

namespace abu {

/// `text` with every control character (and DEL) written as an escape (\n, \t, \xHH), for
/// terminal messages and CSV comment lines: a scene string or path cannot start a line.
std::string escaped(std::string_view text);

}  // namespace abu
