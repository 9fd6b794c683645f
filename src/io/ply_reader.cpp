// SPDX-License-Identifier: AGPL-3.0-or-later
// Stanford PLY: ascii, binary_little_endian and binary_big_endian. Reads x, y, z of the `vertex`
// element (any scalar type) and the `vertex_indices` (or `vertex_index`) list of the `face` element
// (any count and index types); also decodes `tristrips`. Every other property and element is
// skipped by its declared layout. Counts in the header are checked against the file size before
// anything is allocated.

#include "io/io_detail.h"

#include <array>
#include <string>
#include <vector>

namespace meshquilt::io_detail {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parse_type(std::string_view name, PlyType& type) {
    struct Entry {
        const char* a;
        const char* b;
        PlyType type;
    };
    static const std::array<Entry, 8> kTypes{{{"char", "int8", PlyType::Int8},
                                              {"uchar", "uint8", PlyType::UInt8},
                                              {"short", "int16", PlyType::Int16},
                                              {"ushort", "uint16", PlyType::UInt16},
                                              {"int", "int32", PlyType::Int32},
                                              {"uint", "uint32", PlyType::UInt32},
                                              {"float", "float32", PlyType::Float32},
                                              {"double", "float64", PlyType::Float64}}};
    for (const Entry& e : kTypes)
        if (name == e.a || name == e.b) {
            type = e.type;
            return true;
        }
    return false;
}

std::size_t type_size(PlyType t) {
    switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
    }
    return 8;
}

struct Property {
    std::string name;
    bool is_list = false;
    PlyType type = PlyType::Float32;        // of the value, or of the list items
    PlyType count_type = PlyType::UInt8;    // lists only
};

struct Element {
    std::string name;
    long long count = 0;
    std::vector<Property> props;
    long line = 0;  // of its header line
};

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::size_t data_offset = 0;
    long data_line = 1;  // line number where ASCII data starts
};

Header parse_header(const std::string& path, std::string_view data) {
    Header h;
    std::size_t pos = 0;
    long line = 0;
    bool have_format = false;
    for (;;) {
        if (pos >= data.size()) fail(path, "truncated header: no 'end_header' line");
        ++line;
        std::size_t eol = data.find('\n', pos);
        if (eol == std::string_view::npos) eol = data.size();
        const std::string_view text = data.substr(pos, eol - pos);
        pos = eol + 1;
        TextScanner scan(text, false, line);
        const std::string_view keyword = scan.next_on_line();
        if (line == 1) {
            if (keyword != "ply" || !scan.next_on_line().empty()) fail(path, "not a PLY file: the first line is not 'ply'");
            continue;
        }
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            if (!have_format) fail_at(path, line, "the header has no 'format' line");
            h.data_offset = pos > data.size() ? data.size() : pos;
            h.data_line = line + 1;
            return h;
        }
        if (keyword == "format") {
            const std::string_view f = scan.next_on_line();
            if (f == "ascii") h.format = Format::Ascii;
            else if (f == "binary_little_endian") h.format = Format::BinaryLittle;
            else if (f == "binary_big_endian") h.format = Format::BinaryBig;
            else fail_at(path, line, "unknown PLY format " + quoted(f));
            have_format = true;
        } else if (keyword == "element") {
            Element e;
            e.name = std::string(scan.next_on_line());
            const std::string_view count = scan.next_on_line();
            if (e.name.empty() || !parse_int(count, e.count) || e.count < 0)
                fail_at(path, line, "bad element line (expected 'element <name> <count>')");
            e.line = line;
            h.elements.push_back(std::move(e));
        } else if (keyword == "property") {
            if (h.elements.empty()) fail_at(path, line, "property before any element");
            Property prop;
            std::string_view type = scan.next_on_line();
            if (type == "list") {
                prop.is_list = true;
                const std::string_view count_type = scan.next_on_line();
                if (!parse_type(count_type, prop.count_type))
                    fail_at(path, line, "unknown list count type " + quoted(count_type));
                if (prop.count_type == PlyType::Float32 || prop.count_type == PlyType::Float64)
                    fail_at(path, line, "list count type must be an integer type, not " + quoted(count_type));
                type = scan.next_on_line();
            }
            if (!parse_type(type, prop.type)) fail_at(path, line, "unknown property type " + quoted(type));
            prop.name = std::string(scan.next_on_line());
            if (prop.name.empty()) fail_at(path, line, "property without a name");
            h.elements.back().props.push_back(std::move(prop));
        } else {
            fail_at(path, line, "unknown header line starting with " + quoted(keyword));
        }
    }
}

/// Binary body: values of any PLY type in either byte order.
class BinarySource {
public:
    BinarySource(const std::string& path, std::string_view data, bool big_endian)
        : path_(path), p_(reinterpret_cast<const unsigned char*>(data.data())), e_(p_ + data.size()) {
        const std::uint16_t probe = 1;
        unsigned char first = 0;
        std::memcpy(&first, &probe, 1);
        swap_ = (first == 1) == big_endian;
    }
    void begin_record(const Element& e, long long index) {
        element_ = &e;
        record_ = index;
    }
    double value(PlyType t) {
        const std::size_t n = type_size(t);
        if (static_cast<std::size_t>(e_ - p_) < n) truncated();
        unsigned char b[8];
        std::memcpy(b, p_, n);
        p_ += n;
        if (swap_)
            for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        switch (t) {
        case PlyType::Int8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
        case PlyType::UInt8: return b[0];
        case PlyType::Int16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
        case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
        case PlyType::Int32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
        case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
        case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
        case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
        }
        return 0.0;
    }
    void skip(PlyType t, long long n) {
        const std::size_t size = type_size(t);
        if (n < 0 || static_cast<unsigned long long>(n) > static_cast<std::size_t>(e_ - p_) / size) truncated();
        p_ += static_cast<std::size_t>(n) * size;
    }
    /// A list length that cannot be right: more items than bytes left.
    [[nodiscard]] bool list_fits(PlyType t, long long n) const {
        return n >= 0 && static_cast<unsigned long long>(n) <= static_cast<std::size_t>(e_ - p_) / type_size(t);
    }
    [[noreturn]] void error(const std::string& what) const {
        fail(path_, element_->name + " " + std::to_string(record_) + ": " + what);
    }
    [[noreturn]] void truncated() const {
        fail(path_, "truncated: header says " + std::to_string(element_->count) + " " + element_->name +
                        " elements, file ends in element " + std::to_string(record_));
    }
    [[nodiscard]] std::size_t remaining() const { return static_cast<std::size_t>(e_ - p_); }

private:
    const std::string& path_;
    const unsigned char* p_;
    const unsigned char* e_;
    bool swap_ = false;
    const Element* element_ = nullptr;
    long long record_ = 0;
};

/// ASCII body: whitespace-separated numbers; records need not follow lines.
class AsciiSource {
public:
    AsciiSource(const std::string& path, std::string_view data, long first_line)
        : path_(path), scan_(data, false, first_line), end_(data.data() + data.size()) {}
    void begin_record(const Element& e, long long index) {
        element_ = &e;
        record_ = index;
    }
    double value(PlyType) {
        const std::string_view token = scan_.next();
        if (token.empty())
            fail(path_, "truncated: header says " + std::to_string(element_->count) + " " + element_->name +
                            " elements, file ends in element " + std::to_string(record_));
        double v = 0.0;
        switch (parse_double(token, v)) {
        case NumberStatus::Ok: return v;
        case NumberStatus::NonFinite: return v;  // the caller decides whether that is allowed
        case NumberStatus::Bad: error("cannot read number " + quoted(token));
        }
        return v;
    }
    void skip(PlyType t, long long n) {
        for (long long i = 0; i < n; ++i) value(t);
    }
    /// Every item needs at least two bytes ("0 ").
    [[nodiscard]] bool list_fits(PlyType, long long n) const {
        return n >= 0 && n <= (end_ - scan_.position() + 1) / 2;
    }
    [[noreturn]] void error(const std::string& what) const { fail_at(path_, scan_.line(), what); }

private:
    const std::string& path_;
    TextScanner scan_;
    const char* end_;
    const Element* element_ = nullptr;
    long long record_ = 0;
};

/// A list length or index must be a non-negative integer that fits in an int.
bool as_index(double v, long long& out) {
    if (!(v >= -2147483648.0 && v <= 2147483647.0) || v != static_cast<double>(static_cast<long long>(v))) return false;
    out = static_cast<long long>(v);
    return true;
}

int find_property(const Element& e, const char* name, bool list) {
    for (std::size_t i = 0; i < e.props.size(); ++i)
        if (e.props[i].name == name && e.props[i].is_list == list) return static_cast<int>(i);
    return -1;
}

template <class Source>
void read_body(const std::string& path, const Header& h, Source& src, Mesh& mesh) {
    const Element* vertex_element = nullptr;
    for (const Element& e : h.elements)
        if (e.name == "vertex") {
            vertex_element = &e;
            break;
        }
    const long long nv = vertex_element ? vertex_element->count : 0;
    std::vector<long long> list;
    for (const Element& e : h.elements) {
        if (e.props.empty()) continue;  // nothing stored per record
        const bool is_vertex = &e == vertex_element;
        const bool is_face = e.name == "face";
        const bool is_strips = e.name == "tristrips";
        std::array<int, 3> xyz{-1, -1, -1};
        int list_prop = -1;
        if (is_vertex) {
            const char* names[3] = {"x", "y", "z"};
            for (int k = 0; k < 3; ++k) {
                xyz[static_cast<std::size_t>(k)] = find_property(e, names[k], false);
                if (xyz[static_cast<std::size_t>(k)] < 0)
                    fail_at(path, e.line, std::string("the vertex element has no scalar '") + names[k] + "' property");
            }
            mesh.vertices.reserve(static_cast<std::size_t>(e.count));
        } else if (is_face || is_strips) {
            list_prop = find_property(e, "vertex_indices", true);
            if (list_prop < 0) list_prop = find_property(e, "vertex_index", true);
            if (list_prop < 0)
                fail_at(path, e.line, "the " + e.name + " element has no 'vertex_indices' (or 'vertex_index') list");
            if (!vertex_element) fail_at(path, e.line, "faces but no vertex element");
            if (is_face) mesh.faces.reserve(mesh.faces.size() + static_cast<std::size_t>(e.count));
        }
        for (long long r = 0; r < e.count; ++r) {
            src.begin_record(e, r);
            double coord[3] = {0.0, 0.0, 0.0};
            for (std::size_t j = 0; j < e.props.size(); ++j) {
                const Property& prop = e.props[j];
                if (!prop.is_list) {
                    const double v = src.value(prop.type);
                    for (int k = 0; k < 3; ++k)
                        if (xyz[static_cast<std::size_t>(k)] == static_cast<int>(j)) coord[k] = v;
                    continue;
                }
                long long n = 0;
                if (!as_index(src.value(prop.count_type), n) || n < 0) src.error("bad list length");
                if (static_cast<int>(j) != list_prop) {
                    src.skip(prop.type, n);
                    continue;
                }
                if (is_face && n < 3)
                    src.error("face with " + std::to_string(n) + " corners (a face needs at least 3)");
                if (!src.list_fits(prop.type, n))
                    src.error("list of " + std::to_string(n) + " indices runs past the end of the file");
                list.resize(static_cast<std::size_t>(n));
                for (long long& index : list) {
                    const double v = src.value(prop.type);
                    if (!as_index(v, index)) src.error("bad vertex index " + std::to_string(v));
                    if (index == -1 && is_strips) continue;  // strip restart
                    if (index < 0 || index >= nv)
                        src.error("face index " + std::to_string(index) + " out of range (the file has " +
                                  std::to_string(nv) + " vertices)");
                }
                if (is_face) {
                    for (std::size_t k = 1; k + 1 < list.size(); ++k)
                        mesh.faces.emplace_back(static_cast<int>(list[0]), static_cast<int>(list[k]),
                                                static_cast<int>(list[k + 1]));
                } else {
                    // Triangle strips: every window of three; odd windows are flipped to keep the
                    // winding; windows with a repeated index only stitch strips together.
                    std::size_t start = 0;
                    for (std::size_t k = 0; k <= list.size(); ++k) {
                        if (k < list.size() && list[k] != -1) continue;
                        for (std::size_t i = start; i + 2 < k; ++i) {
                            const auto a = static_cast<int>(list[i]), b = static_cast<int>(list[i + 1]),
                                       c = static_cast<int>(list[i + 2]);
                            if (a == b || b == c || a == c) continue;
                            if ((i - start) % 2 == 0) mesh.faces.emplace_back(a, b, c);
                            else mesh.faces.emplace_back(b, a, c);
                        }
                        start = k + 1;
                    }
                }
            }
            if (is_vertex) {
                if (!std::isfinite(coord[0]) || !std::isfinite(coord[1]) || !std::isfinite(coord[2]))
                    src.error("non-finite vertex coordinate");
                mesh.vertices.emplace_back(coord[0], coord[1], coord[2]);
            }
        }
    }
}

}  // namespace

Mesh read_ply(const std::string& path, std::string_view data) {
    const Header h = parse_header(path, data);
    const std::string_view body = data.substr(h.data_offset);

    // Reject counts the file cannot hold before reserving anything: every record needs at least
    // its scalars and list lengths (binary) or one token per property (ASCII, two bytes each).
    const unsigned __int128 kHuge = static_cast<unsigned __int128>(1) << 62;
    unsigned __int128 need = 0;
    for (const Element& e : h.elements) {
        std::size_t min_record = 0;
        for (const Property& p : e.props)
            min_record += h.format == Format::Ascii ? 2 : type_size(p.is_list ? p.count_type : p.type);
        need += static_cast<unsigned __int128>(e.count) * min_record;
        if ((e.name == "vertex" || e.name == "face") && e.count > kMaxElements)
            fail_at(path, e.line, "header says " + std::to_string(e.count) + " " + e.name + " elements (the limit is 2^31 - 1)");
        if (need > static_cast<unsigned __int128>(body.size()) + 1)
            fail(path, "truncated: header says " + std::to_string(e.count) + " " + e.name + " elements, which need " +
                           (need > kHuge ? std::string("more than 2^62") : "at least " + std::to_string(static_cast<unsigned long long>(need))) +
                           " bytes, but only " + std::to_string(body.size()) + " bytes follow the header");
    }
    bool has_faces = false;
    for (const Element& e : h.elements) has_faces = has_faces || e.name == "face" || e.name == "tristrips";
    if (!has_faces) fail(path, "no faces (the header declares no face element)");

    Mesh mesh;
    if (h.format == Format::Ascii) {
        AsciiSource src(path, body, h.data_line);
        read_body(path, h, src, mesh);
    } else {
        BinarySource src(path, body, h.format == Format::BinaryBig);
        read_body(path, h, src, mesh);
    }
    return mesh;
}

}  // namespace meshquilt::io_detail
