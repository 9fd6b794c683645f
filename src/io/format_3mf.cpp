// SPDX-License-Identifier: AGPL-3.0-or-later
// 3MF through lib3mf (Debian ships the 1.8 "NMR" C interface). Written in millimetres, one mesh
// object per element, serialised to memory and then written atomically like every other format.
// Read: every build item's mesh object with its transform, concatenated.

#include "io/io_detail.h"
#include "meshquilt/io.h"

#include <Model/COM/NMR_DLLInterfaces.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>

namespace meshquilt::io_detail {

namespace {

/// Releases a lib3mf instance when it goes out of scope.
struct Released {
    NMR::PLib3MFBase* p = nullptr;
    ~Released() {
        if (p) NMR::lib3mf_release(p);
    }
};

std::string last_error(NMR::PLib3MFBase* instance) {
    DWORD code = 0;
    LPCSTR text = nullptr;
    if (instance && NMR::lib3mf_getlasterror(instance, &code, &text) == LIB3MF_OK && text && *text) return text;
    return "error " + std::to_string(code);
}

void ok(HRESULT r, const std::string& path, const char* what, NMR::PLib3MFBase* instance) {
    if (r != LIB3MF_OK) throw IoError(path + ": 3MF: " + what + " failed: " + last_error(instance));
}

/// The transform `outer` after `inner` (3MF transforms: rows of a 3 x 4 affine matrix).
NMR::MODELTRANSFORM compose(const NMR::MODELTRANSFORM& outer, const NMR::MODELTRANSFORM& inner) {
    NMR::MODELTRANSFORM r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            float v = j == 3 ? outer.m_fFields[i][3] : 0.0f;
            for (int k = 0; k < 3; ++k) v += outer.m_fFields[i][k] * inner.m_fFields[k][j];
            r.m_fFields[i][j] = v;
        }
    return r;
}

/// A UUID (version 4 layout) drawn from a hash of the geometry and a counter, so the same mesh
/// gives the same file (lib3mf would draw random ones, and output must be reproducible).
class UuidSource {
public:
    explicit UuidSource(const Mesh& mesh) {
        std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the coordinates and faces
        const auto mix = [&h](const void* p, std::size_t n) {
            const auto* b = static_cast<const unsigned char*>(p);
            for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
        };
        if (!mesh.vertices.empty()) mix(mesh.vertices.data(), mesh.vertices.size() * sizeof(Vec3));
        if (!mesh.faces.empty()) mix(mesh.faces.data(), mesh.faces.size() * sizeof(Tri));
        state_ = h;
    }
    std::string next() {
        const std::uint64_t a = step(), b = step();
        char buf[40];
        std::snprintf(buf, sizeof buf, "%08x-%04x-4%03x-%04x-%012llx", static_cast<unsigned>(a >> 32), static_cast<unsigned>((a >> 16) & 0xffff),
                      static_cast<unsigned>(a & 0xfff), static_cast<unsigned>(0x8000 | ((b >> 48) & 0x3fff)),
                      static_cast<unsigned long long>(b & 0xffffffffffffull));
        return buf;
    }

private:
    std::uint64_t step() {  // splitmix64
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    std::uint64_t state_;
};

}  // namespace

std::string format_3mf(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
    NMR::PLib3MFModel* model = nullptr;
    ok(NMR::lib3mf_createmodel(&model), path, "creating the model", nullptr);
    Released model_guard{model};
    ok(NMR::lib3mf_model_setunit(model, NMR::MODELUNIT_MILLIMETER), path, "setting the unit", model);
    UuidSource uuid(mesh);
    ok(NMR::lib3mf_model_setbuilduuidutf8(model, uuid.next().c_str()), path, "setting the build's UUID", model);

    // Faces by element, in increasing id order (one object each); no elements: one object.
    std::map<int, std::vector<std::size_t>> faces_of;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        faces_of[options.element_of_face.empty() ? 0 : options.element_of_face[f]].push_back(f);
    const auto add_item = [&](NMR::PLib3MFModelObjectResource* object) {
        NMR::PLib3MFModelBuildItem* item = nullptr;
        ok(NMR::lib3mf_model_addbuilditem(model, object, nullptr, &item), path, "adding a build item", model);
        Released item_guard{item};
        ok(NMR::lib3mf_builditem_setuuidutf8(item, uuid.next().c_str()), path, "setting a build item's UUID", item);
    };
    // 3MF resources must come before what refers to them: the assembly is added after its parts.
    const bool assembly = options.assembly_3mf && faces_of.size() > 1;
    std::vector<std::unique_ptr<Released>> parts;
    std::vector<int> index(mesh.vertices.size(), -1);
    for (const auto& [id, faces] : faces_of) {
        std::vector<NMR::MODELMESHVERTEX> verts;
        std::vector<NMR::MODELMESHTRIANGLE> tris;
        std::vector<int> used;
        for (std::size_t f : faces) {
            NMR::MODELMESHTRIANGLE t{};
            for (int k = 0; k < 3; ++k) {
                const auto v = static_cast<std::size_t>(mesh.faces[f][k]);
                if (index[v] < 0) {
                    index[v] = static_cast<int>(verts.size());
                    used.push_back(static_cast<int>(v));
                    NMR::MODELMESHVERTEX mv{};
                    for (int c = 0; c < 3; ++c) mv.m_fPosition[c] = static_cast<float>(mesh.vertices[v][c]);
                    verts.push_back(mv);
                }
                t.m_nIndices[k] = static_cast<DWORD>(index[v]);
            }
            tris.push_back(t);
        }
        for (int v : used) index[static_cast<std::size_t>(v)] = -1;
        NMR::PLib3MFModelMeshObject* object = nullptr;
        ok(NMR::lib3mf_model_addmeshobject(model, &object), path, "adding an object", model);
        parts.push_back(std::make_unique<Released>());
        parts.back()->p = object;
        std::string name = options.element_of_face.empty() ? "meshquilt" : "element_" + std::to_string(id);
        if (id >= 0 && static_cast<std::size_t>(id) < options.group_names.size() && !options.group_names[static_cast<std::size_t>(id)].empty())
            name = options.group_names[static_cast<std::size_t>(id)];
        ok(NMR::lib3mf_object_setnameutf8(object, name.c_str()), path, "naming an object", object);
        ok(NMR::lib3mf_object_setuuidutf8(object, uuid.next().c_str()), path, "setting an object's UUID", object);
        ok(NMR::lib3mf_meshobject_setgeometry(object, verts.data(), static_cast<DWORD>(verts.size()), tris.data(),
                                              static_cast<DWORD>(tris.size())),
           path, "setting an object's geometry", object);
        if (!assembly) add_item(object);
    }
    if (assembly) {
        NMR::PLib3MFModelComponentsObject* whole = nullptr;
        ok(NMR::lib3mf_model_addcomponentsobject(model, &whole), path, "adding the assembly", model);
        Released whole_guard{whole};
        ok(NMR::lib3mf_object_setnameutf8(whole, "meshquilt"), path, "naming the assembly", whole);
        ok(NMR::lib3mf_object_setuuidutf8(whole, uuid.next().c_str()), path, "setting the assembly's UUID", whole);
        for (const auto& part : parts) {
            NMR::PLib3MFModelComponent* component = nullptr;
            ok(NMR::lib3mf_componentsobject_addcomponent(whole, part->p, nullptr, &component), path, "adding a component", whole);
            Released component_guard{component};
            ok(NMR::lib3mf_component_setuuidutf8(component, uuid.next().c_str()), path, "setting a component's UUID", component);
        }
        add_item(whole);
    }

    NMR::PLib3MFModelWriter* writer = nullptr;
    ok(NMR::lib3mf_model_querywriter(model, "3mf", &writer), path, "creating the writer", model);
    Released writer_guard{writer};
    ULONG64 size = 0;
    ok(NMR::lib3mf_writer_getstreamsize(writer, &size), path, "sizing the file", writer);
    std::string bytes(static_cast<std::size_t>(size), '\0');
    ok(NMR::lib3mf_writer_writetobuffer(writer, reinterpret_cast<BYTE*>(bytes.data()), size), path, "writing", writer);
    return bytes;
}

Mesh read_3mf(const std::string& path, std::string_view data) {
    NMR::PLib3MFModel* model = nullptr;
    ok(NMR::lib3mf_createmodel(&model), path, "creating the model", nullptr);
    Released model_guard{model};
    NMR::PLib3MFModelReader* reader = nullptr;
    ok(NMR::lib3mf_model_queryreader(model, "3mf", &reader), path, "creating the reader", model);
    Released reader_guard{reader};
    std::string copy(data);  // lib3mf wants a mutable buffer
    if (NMR::lib3mf_reader_readfrombuffer(reader, reinterpret_cast<BYTE*>(copy.data()), copy.size()) != LIB3MF_OK)
        fail(path, "not a readable 3MF file: " + last_error(reader));
    NMR::PLib3MFModelBuildItemIterator* items = nullptr;
    ok(NMR::lib3mf_model_getbuilditems(model, &items), path, "listing the build items", model);
    Released items_guard{items};
    Mesh out;
    const auto append_mesh = [&](NMR::PLib3MFModelObjectResource* object, const NMR::MODELTRANSFORM& xf) {
        DWORD nv = 0, nt = 0;
        ok(NMR::lib3mf_meshobject_getvertexcount(object, &nv), path, "reading the vertex count", object);
        ok(NMR::lib3mf_meshobject_gettrianglecount(object, &nt), path, "reading the triangle count", object);
        std::vector<NMR::MODELMESHVERTEX> verts(nv);
        std::vector<NMR::MODELMESHTRIANGLE> tris(nt);
        if (nv) ok(NMR::lib3mf_meshobject_getvertices(object, verts.data(), nv, nullptr), path, "reading vertices", object);
        if (nt) ok(NMR::lib3mf_meshobject_gettriangleindices(object, tris.data(), nt, nullptr), path, "reading triangles", object);
        const int base = static_cast<int>(out.vertices.size());
        for (const auto& v : verts) {
            Vec3 p;
            for (int r = 0; r < 3; ++r)
                p[r] = xf.m_fFields[r][0] * v.m_fPosition[0] + xf.m_fFields[r][1] * v.m_fPosition[1] + xf.m_fFields[r][2] * v.m_fPosition[2] +
                       xf.m_fFields[r][3];
            out.vertices.push_back(p);
        }
        for (const auto& t : tris) {
            for (int k = 0; k < 3; ++k)
                if (t.m_nIndices[k] >= nv) fail(path, "a triangle's vertex index is out of range");
            out.faces.emplace_back(base + static_cast<int>(t.m_nIndices[0]), base + static_cast<int>(t.m_nIndices[1]),
                                   base + static_cast<int>(t.m_nIndices[2]));
        }
    };
    BOOL more = false;
    while (NMR::lib3mf_builditemiterator_movenext(items, &more) == LIB3MF_OK && more) {
        NMR::PLib3MFModelBuildItem* item = nullptr;
        ok(NMR::lib3mf_builditemiterator_getcurrent(items, &item), path, "reading a build item", items);
        Released item_guard{item};
        NMR::PLib3MFModelObjectResource* object = nullptr;
        ok(NMR::lib3mf_builditem_getobjectresource(item, &object), path, "reading a build item's object", item);
        Released object_guard{object};
        NMR::MODELTRANSFORM xf{};
        ok(NMR::lib3mf_builditem_getobjecttransform(item, &xf), path, "reading a build item's transform", item);
        BOOL is_mesh = false;
        ok(NMR::lib3mf_object_ismeshobject(object, &is_mesh), path, "reading an object's type", object);
        if (is_mesh) {
            append_mesh(object, xf);
            continue;
        }
        // An assembly: its components (mesh objects; one level deep), each with its transform
        // followed by the build item's.
        DWORD count = 0;
        ok(NMR::lib3mf_componentsobject_getcomponentcount(object, &count), path, "reading an assembly", object);
        for (DWORD c = 0; c < count; ++c) {
            NMR::PLib3MFModelComponent* component = nullptr;
            ok(NMR::lib3mf_componentsobject_getcomponent(object, c, &component), path, "reading a component", object);
            Released component_guard{component};
            NMR::PLib3MFModelObjectResource* part = nullptr;
            ok(NMR::lib3mf_component_getobjectresource(component, &part), path, "reading a component's object", component);
            Released part_guard{part};
            BOOL part_is_mesh = false;
            ok(NMR::lib3mf_object_ismeshobject(part, &part_is_mesh), path, "reading an object's type", part);
            if (!part_is_mesh) fail(path, "an assembly nests another assembly; only one level is supported");
            NMR::MODELTRANSFORM cx{};
            ok(NMR::lib3mf_component_gettransform(component, &cx), path, "reading a component's transform", component);
            append_mesh(part, compose(xf, cx));
        }
    }
    return out;
}

}  // namespace meshquilt::io_detail
