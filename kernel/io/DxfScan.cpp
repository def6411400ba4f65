#include "io/DxfScan.h"

#include "io/DxfCodes.h"
#include "io/IoText.h"
#include "model/Error.h"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace netsculpt::io {

namespace {

constexpr std::size_t kMaxLine = 1000; // dxflib reads lines into a 1024-byte buffer
constexpr long long kMaxCount = 10'000'000;

class Scanner {
  public:
    Scanner(const std::string& file, const std::string& text) : file_(file), text_(text) {}

    DxfScan run() {
        if (text_.rfind("AutoCAD Binary DXF", 0) == 0)
            fail(1, "is a binary DXF; save the drawing as ASCII DXF");
        splitLines();
        if (!parseInteger(lines_[0]))
            fail(1, "is not an ASCII DXF file: the first line should be a group code (an integer), "
                    "it is " +
                        quoted(lines_[0]));
        for (std::size_t i = 0; i + 1 < lines_.size() && !ended_; i += 2)
            group(i);
        if (!ended_) {
            if (lines_.size() % 2 == 1 && !ended_)
                fail(lines_.size(), "the file ends in the middle of a group (a code without its "
                                    "value); it is truncated");
            fail(lines_.size(),
                 std::string("the file ends ") +
                     (section_.empty() ? "" : "inside the " + section_ + " section ") +
                     "without the closing '0 EOF'; it is truncated");
        }
        if (!sawSection_)
            fail(1, "holds no SECTION; this is not a DXF file");
        finishEntity();
        out_.lines = lines_.size();
        return std::move(out_);
    }

  private:
    const std::string& file_;
    const std::string& text_;
    std::vector<std::string_view> lines_;
    DxfScan out_;
    std::string section_; // current section's name, "" outside
    bool expectName_ = false;
    bool sawSection_ = false;
    bool ended_ = false;
    bool inEntity_ = false;
    DxfEntity entity_;
    std::string object_;                        // type of the current object (entity, table entry)
    std::size_t objectLine_ = 0;                // the line of its "0" group code
    std::array<std::size_t, 100> countLines_{}; // line of each allocated count it gave; 0 = none
    bool inBlock_ = false;                      // between BLOCK and ENDBLK
    std::string block_;                         // the current block's name
    std::size_t blockEntities_ = 0, modelEntities_ = 0;
    DxfLayer layer_;             // the LAYER table entry being read
    bool netsculptData_ = false; // the entity's extended data being read is NETSCULPT's

    [[noreturn]] void fail(std::size_t line, const std::string& what) const {
        throw UserError(file_ + ": line " + std::to_string(line) + ": " + what);
    }

    void splitLines() {
        if (text_.empty())
            throw UserError(file_ + ": the file is empty; expected an ASCII DXF drawing");
        if (text_.find('\0') != std::string::npos)
            fail(1 + std::size_t(std::count(
                         text_.begin(), text_.begin() + std::ptrdiff_t(text_.find('\0')), '\n')),
                 "holds binary data (a NUL byte); expected an ASCII DXF drawing");
        std::size_t start = 0;
        while (start < text_.size()) {
            std::size_t end = text_.find('\n', start);
            if (end == std::string::npos)
                end = text_.size();
            std::string_view line(text_.data() + start, end - start);
            if (!line.empty() && line.back() == '\r')
                line.remove_suffix(1);
            if (line.size() > kMaxLine)
                fail(lines_.size() + 1, "is " + std::to_string(line.size()) +
                                            " characters long; DXF lines "
                                            "are at most " +
                                            std::to_string(kMaxLine));
            lines_.push_back(line);
            start = end + 1;
        }
    }

    void group(std::size_t i) {
        const std::size_t codeLine = i + 1;
        const auto code = parseInteger(lines_[i]);
        if (!code || *code < 0 || *code > 1071) {
            if (i == 0)
                fail(1, "is not an ASCII DXF file: the first line should be a group code (an "
                        "integer), it is " +
                            quoted(lines_[i]));
            fail(codeLine, "expected a DXF group code (an integer from 0 to 1071), found " +
                               quoted(lines_[i]));
        }
        const int c = int(*code);
        const std::string_view value = lines_[i + 1];
        if (c == 999)
            return; // comment
        if (expectName_) {
            if (c != 2)
                fail(codeLine, "a SECTION must be followed by its name (group code 2)");
            section_ = std::string(trim(value));
            expectName_ = false;
            return;
        }
        if (c == 0) {
            zero(codeLine, trim(value));
            return;
        }
        if (section_.empty())
            fail(codeLine, "group code " + std::to_string(c) +
                               " outside any SECTION; expected '0 SECTION' or '0 EOF'");
        checkAllocatedCount(codeLine + 1, c, value);
        if (inEntity_)
            entityValue(codeLine + 1, c, value);
        else if (object_ == "BLOCK" && c == 2 && block_.empty())
            block_ = std::string(trim(value));
        else if (object_ == "LAYER" && section_ == "TABLES")
            layerValue(c, value);
    }

    /// Group 2 (name), 70 (flags), 62 (colour) of a LAYER table entry.
    void layerValue(int c, std::string_view value) {
        if (c == 2)
            layer_.name = std::string(trim(value));
        else if (c == 70)
            layer_.flags = int(parseInteger(value).value_or(0));
        else if (c == 62)
            layer_.colour = parseInteger(value).value_or(7);
    }

    void finishObject() {
        if (object_ == "LAYER" && section_ == "TABLES" && !layer_.name.empty())
            out_.layers.push_back(layer_);
        layer_ = DxfLayer();
    }

    void zero(std::size_t line, std::string_view value) {
        if (section_.empty()) {
            if (value == "SECTION") {
                sawSection_ = true;
                expectName_ = true;
            } else if (value == "EOF") {
                ended_ = true;
            } else {
                fail(line, "expected '0 SECTION' or '0 EOF', found '0 " +
                               std::string(value.substr(0, 40)) + "'");
            }
            return;
        }
        finishObject();
        finishEntity();
        if (value == "ENDSEC") {
            section_.clear();
            object_.clear();
            inBlock_ = false;
            return;
        }
        if (value == "SECTION" || value == "EOF")
            fail(line, "'0 " + std::string(value) + "' inside the " + section_ +
                           " section (its ENDSEC is missing)");
        object_ = std::string(value);
        objectLine_ = line;
        countLines_.fill(0);
        if (section_ == "BLOCKS" && (value == "BLOCK" || value == "ENDBLK")) {
            inBlock_ = value == "BLOCK";
            block_.clear();
            blockEntities_ = 0;
            return;
        }
        if (section_ != "ENTITIES" && !(section_ == "BLOCKS" && inBlock_))
            return;
        entity_ = DxfEntity();
        entity_.type = std::string(value);
        entity_.line = line;
        entity_.block = section_ == "BLOCKS" ? block_ : std::string();
        entity_.index = section_ == "BLOCKS" ? blockEntities_++ : modelEntities_++;
        inEntity_ = true;
        netsculptData_ = false;
    }

    /// "LWPOLYLINE on layer R (line 5)" in ENTITIES, "LEADER in the BLOCKS section (line 9)"
    /// elsewhere.
    std::string describeObject() const {
        if (inEntity_)
            return entity_.describe();
        return object_ + " in the " + section_ + " section (line " + std::to_string(objectLine_) +
               ")";
    }

    /// dxflib allocates an array by each of these counts as it reads it, in any section, and
    /// frees the old array first when a count comes again: a count of 2e9 asked for 64 GB, and
    /// when that allocation failed after a first count, dxflib freed its array a second time.
    /// So every count is checked wherever it is, and may be given once per object.
    void checkAllocatedCount(std::size_t line, int c, std::string_view value) {
        const char* what = allocatedCount(object_, c);
        if (!what)
            return;
        const auto number = parseInteger(value);
        if (!number)
            fail(line, describeObject() + ": " + what + " (group code " + std::to_string(c) +
                           ") holds " + quoted(value) + ", which is not an integer");
        if (*number < 0 || *number > kMaxCount)
            fail(line, describeObject() + ": " + what + " " + std::to_string(*number) +
                           " (group code " + std::to_string(c) +
                           ") is out of range; allowed 0 to " + std::to_string(kMaxCount));
        std::size_t& first = countLines_[std::size_t(c)];
        if (first != 0)
            fail(line, describeObject() + ": gives its " + what + " (group code " +
                           std::to_string(c) + ") twice, at lines " + std::to_string(first) +
                           " and " + std::to_string(line) + "; an entity declares it once");
        first = line;
    }

    void entityValue(std::size_t line, int c, std::string_view value) {
        if (isRealCode(c)) {
            const auto number = parseDouble(value);
            if (!number)
                fail(line, entity_.describe() + ": group code " + std::to_string(c) + " (" +
                               codeMeaning(c) + ") holds " + quoted(value) +
                               ", which is not a number");
            if (!std::isfinite(*number))
                fail(line, entity_.describe() + ": group code " + std::to_string(c) + " (" +
                               codeMeaning(c) + ") is " + quoted(value) +
                               "; it must be a finite number");
        } else if (isIntegerCode(c)) {
            const auto number = parseInteger(value);
            if (!number)
                fail(line, entity_.describe() + ": group code " + std::to_string(c) + " holds " +
                               quoted(value) + ", which is not an integer");
            if (c >= 60 && c <= 99 && entity_.integer[std::size_t(c - 60)] == -1) {
                if ((c >= 72 && c <= 74) || c == 90) {
                    if (*number < 0 || *number > kMaxCount)
                        fail(line, entity_.describe() + ": count " + std::to_string(*number) +
                                       " (group code " + std::to_string(c) +
                                       ") is out of range; allowed 0 to " +
                                       std::to_string(kMaxCount));
                }
                entity_.integer[std::size_t(c - 60)] = *number;
            }
        }
        if (c < 100)
            ++entity_.count[std::size_t(c)];
        if (c == 5 && entity_.handle.empty())
            entity_.handle = std::string(trim(value));
        if (c == 8)
            entity_.layer = std::string(trim(value));
        if (c == 67)
            entity_.paperSpace = trim(value) == "1";
        if (c == 1001)
            netsculptData_ = trim(value) == kDxfApplication;
        if (c == 1000 && netsculptData_)
            entity_.netsculptMark.emplace_back(value);
    }

    void checkCount(const DxfEntity& e, int declaredCode, int valueCode, const char* what) {
        const long long declared = e.declared(declaredCode);
        const int present = e.count[std::size_t(valueCode)];
        if (declared >= 0 && declared != present)
            fail(e.line, e.describe() + ": declares " + std::to_string(declared) + " " + what +
                             " (group code " + std::to_string(declaredCode) + ") but lists " +
                             std::to_string(present) + " (group code " + std::to_string(valueCode) +
                             ")");
    }

    void finishEntity() {
        if (!inEntity_)
            return;
        inEntity_ = false;
        const DxfEntity& e = entity_;
        if (e.type == "SPLINE") {
            if (e.declared(73) < 0 && e.count[10] > 0)
                fail(e.line,
                     e.describe() + ": lists control points but not their count (group code 73)");
            if (e.declared(72) < 0 && e.count[40] > 0)
                fail(e.line, e.describe() + ": lists knots but not their count (group code 72)");
            checkCount(e, 73, 10, "control points");
            checkCount(e, 72, 40, "knots");
            checkCount(e, 74, 11, "fit points");
            if (e.count[41] != 0 && e.count[41] != e.count[10])
                fail(e.line, e.describe() + ": lists " + std::to_string(e.count[41]) +
                                 " weights for " + std::to_string(e.count[10]) +
                                 " control points; give one weight per control "
                                 "point, or none");
        } else if (e.type == "LWPOLYLINE") {
            checkCount(e, 90, 10, "vertices");
        }
        out_.byLine[e.line] = out_.entities.size();
        out_.entities.push_back(e);
    }
};

} // namespace

std::string DxfEntity::describe() const {
    std::string text = type;
    if (!handle.empty())
        text += " " + handle;
    text += " on layer " + layer + " (line " + std::to_string(line) + ")";
    return block.empty() ? text : text + " in block " + block;
}

std::string DxfEntity::handleOrIndex() const {
    return handle.empty() ? concat({"#", std::to_string(index + 1)}) : handle;
}

std::string DxfEntity::railName() const {
    if (netsculptMark.size() == 2 && netsculptMark[0] == "rail" && !netsculptMark[1].empty())
        return netsculptMark[1];
    return concat({layer, ":", handleOrIndex()});
}

bool DxfEntity::netsculptBar() const {
    return netsculptMark.size() == 1 && netsculptMark[0] == "bar";
}

DxfScan scanDxf(const std::string& file, const std::string& text) {
    return Scanner(file, text).run();
}

} // namespace netsculpt::io
