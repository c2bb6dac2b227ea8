#include "demlight/core/error.h"

namespace demlight {

std::string renderNames(const std::string& text, const std::function<std::string(const std::string&)>& spell) {
    const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || c == '_'; };
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '{') {
            std::size_t j = i + 1;
            while (j < text.size() && (letter(text[j]) || (j > i + 1 && text[j] >= '0' && text[j] <= '9'))) ++j;
            if (j > i + 1 && j < text.size() && text[j] == '}') {
                out += spell(text.substr(i + 1, j - i - 1));
                i = j;
                continue;
            }
        }
        out += text[i];
    }
    return out;
}

}  // namespace demlight
