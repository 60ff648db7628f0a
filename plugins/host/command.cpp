#include "plugins/host/command.hpp"

namespace weft {

CommandRegistry& commands() {
    static CommandRegistry registry("command");
    return registry;
}

int& commandExitStatus() {
    static int status = 0;
    return status;
}

std::pair<std::string, std::string> splitKeyValue(const std::string& text, const std::string& option) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0) throw Error(option + " '" + text + "': expected key=value");
    return {text.substr(0, eq), text.substr(eq + 1)};
}

}  // namespace weft
