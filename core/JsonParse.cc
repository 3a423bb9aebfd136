#include "core/JsonParse.h"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/Error.h"

namespace cg {

namespace {

using Json = nlohmann::json;

/// Builds the DOM itself so it can refuse duplicate keys and deep nesting while parsing,
/// and knows the JSON pointer of every value.
class StrictSax final : public nlohmann::json_sax<Json> {
public:
    StrictSax(const std::string& text, const std::string& sourceName, int maxDepth)
        : mText(text), mSource(sourceName), mMaxDepth(maxDepth)
    {
    }

    Json& result() { return mRoot; }

    bool null() override { return put(Json(nullptr)); }
    bool boolean(bool v) override { return put(Json(v)); }
    bool number_integer(number_integer_t v) override { return put(Json(v)); }
    bool number_unsigned(number_unsigned_t v) override { return put(Json(v)); }
    bool number_float(number_float_t v, const string_t&) override { return put(Json(v)); }
    bool string(string_t& v) override { return put(Json(std::move(v))); }
    bool binary(binary_t&) override { return false; }  // text input never produces binary

    bool start_object(std::size_t) override { return open(Json::object()); }
    bool start_array(std::size_t) override { return open(Json::array()); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& k) override
    {
        Frame& top = mStack.back();
        if (top.value->contains(k)) {
            throw InputError(mSource + ":" + pointer() + "/" + jsonPointerToken(k),
                             "duplicate key '" + k + "'");
        }
        top.key = k;
        return true;
    }

    bool parse_error(std::size_t position, const std::string& lastToken,
                     const nlohmann::detail::exception& ex) override
    {
        const auto [line, column] = lineAndColumn(position);
        const std::string lineText =
            "line " + std::to_string(line) + ", column " + std::to_string(column);
        const std::string byteText = "byte " + std::to_string(position);
        if (ex.id == 406) {
            // nlohmann refuses numbers that overflow a double; say where it was, by pointer.
            throw InputError(
                mSource + ":" + pendingPointer(),
                "number " + lastToken + " is not finite (" + lineText + ", " + byteText + ")");
        }
        throw InputError(mSource + ":" + lineText + " (" + byteText + ")",
                         "invalid JSON: " + cleanMessage(ex.what()));
    }

private:
    struct Frame {
        Json* value;
        std::string key;        ///< objects: the key of the value being read
        std::size_t index = 0;  ///< arrays: the index of the next element
    };

    /// Pointer of the innermost open container.
    std::string pointer() const
    {
        std::string p;
        for (std::size_t i = 0; i + 1 < mStack.size(); ++i) p += "/" + token(mStack[i]);
        return p;
    }
    /// Pointer of the value about to be read.
    std::string pendingPointer() const
    {
        std::string p;
        for (const Frame& f : mStack) p += "/" + token(f);
        return p;
    }
    static std::string token(const Frame& f)
    {
        return f.value->is_object() ? jsonPointerToken(f.key) : std::to_string(f.index);
    }

    /// Stores a value at the current place; returns where it went.
    Json* place(Json&& v)
    {
        if (mStack.empty()) {
            mRoot = std::move(v);
            return &mRoot;
        }
        Frame& top = mStack.back();
        if (top.value->is_object()) return &((*top.value)[top.key] = std::move(v));
        top.value->push_back(std::move(v));
        ++top.index;
        return &top.value->back();
    }
    bool put(Json&& v)
    {
        place(std::move(v));
        return true;
    }
    bool open(Json&& container)
    {
        if (static_cast<int>(mStack.size()) >= mMaxDepth) {
            throw InputError(mSource + ":" + (mStack.empty() ? "/" : pendingPointer()),
                             "JSON nests deeper than " + std::to_string(mMaxDepth) + " levels");
        }
        const bool inArray = !mStack.empty() && mStack.back().value->is_array();
        Json* slot = place(std::move(container));
        // The array index was advanced by place(); elements of the new container come later.
        if (inArray) --mStack.back().index;
        mStack.push_back(Frame{slot, {}, 0});
        return true;
    }
    bool close()
    {
        mStack.pop_back();
        if (!mStack.empty() && mStack.back().value->is_array()) ++mStack.back().index;
        return true;
    }

    /// 1-based line and column of nlohmann's 1-based byte position of the last read character.
    std::pair<std::size_t, std::size_t> lineAndColumn(std::size_t position) const
    {
        const std::size_t i = std::min(position == 0 ? 0 : position - 1, mText.size());
        std::size_t line = 1;
        std::size_t lineStart = 0;
        for (std::size_t k = 0; k < i; ++k) {
            if (mText[k] == '\n') {
                ++line;
                lineStart = k + 1;
            }
        }
        return {line, i - lineStart + 1};
    }
    /// Drops nlohmann's "[json.exception...] parse error at line L, column C: " prefix.
    static std::string cleanMessage(std::string msg)
    {
        if (!msg.empty() && msg[0] == '[') {
            const auto end = msg.find("] ");
            if (end != std::string::npos) msg.erase(0, end + 2);
        }
        if (msg.rfind("parse error", 0) == 0) {
            const auto colon = msg.find(": ");
            if (colon != std::string::npos) msg.erase(0, colon + 2);
        }
        return msg;
    }

    const std::string& mText;
    const std::string& mSource;
    int mMaxDepth;
    Json mRoot;
    std::vector<Frame> mStack;
};

}  // namespace

Json parseJsonStrict(const std::string& text, const std::string& sourceName, int maxDepth)
{
    const bool blank = std::all_of(text.begin(), text.end(), [](char c) {
        return std::isspace(static_cast<unsigned char>(c)) != 0;
    });
    if (blank) throw InputError(sourceName, "file is empty");
    StrictSax sax(text, sourceName, maxDepth);
    // The handler throws on every error, so a false return here means nlohmann gave up
    // without reporting, which it does not; stay safe anyway.
    if (!Json::sax_parse(text, &sax)) throw InputError(sourceName, "invalid JSON");
    return std::move(sax.result());
}

std::string printableText(const std::string& text)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string printable;
    printable.reserve(text.size());
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && ch != '\n' && ch != '\t') || c == 0x7f) {
            printable += "\\x";
            printable += kHex[c >> 4];
            printable += kHex[c & 15];
        } else {
            printable += ch;
        }
    }
    return printable;
}

std::string jsonPointerToken(const std::string& key)
{
    std::string out;
    out.reserve(key.size());
    for (char c : key) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

namespace {
std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diag = up;
        }
    }
    return row[b.size()];
}
}  // namespace

std::string closestName(const std::string& word, const std::vector<std::string>& candidates)
{
    std::string best;
    std::size_t bestDistance = 3;
    for (const std::string& c : candidates) {
        const std::size_t d = editDistance(word, c);
        if (d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    return best;
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates)
{
    const std::string best = closestName(word, candidates);
    return best.empty() ? std::string() : "; did you mean '" + best + "'?";
}

}  // namespace cg
