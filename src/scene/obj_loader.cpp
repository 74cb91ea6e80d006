#include "scene/obj_loader.h"

#include <sys/stat.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/files.h"
#include "core/memory_budget.h"
#include "scene/fresnel.h"
#include "scene/microfacet.h"
#include "scene/obj_scan.h"
#include "scene/scene.h"
#include "scene/texture.h"

namespace pt {
namespace {

/// An MTL file larger than this is not a material library (a typical one is
/// a few kilobytes; 16 MiB is thousands of materials).
constexpr uint64_t kMaxMtlBytes = 16 << 20;

/// Reads the OBJ's material libraries for tinyobjloader, with the checks its
/// own reader skips (issue 22): a regular file of bounded size (mtllib
/// /dev/zero grew memory without bound, a fifo hung), and an index of
/// refraction Ni that is a finite number >= 0 (a negative one silently
/// became 1.5). Remembers which materials gave Ni.
class CheckedMaterialReader : public tinyobj::MaterialReader {
public:
    CheckedMaterialReader(std::string directory, std::string where)
        : directory_(std::move(directory)), where_(std::move(where)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string* warn, std::string* err) override {
        const std::string path = name.empty() || name[0] != '/' ? directory_ + name : name;
        struct stat st;
        if (stat(path.c_str(), &st) != 0 && errno == ENOENT)
            throw InputError(where_ + ": material library '" + name + "' not found (" + path + ")");
        std::istringstream text(read_small_file(path, where_ + ": mtllib", kMaxMtlBytes, "a material library"));
        check_ior(text.str(), path);
        tinyobj::LoadMtl(names, materials, &text, warn, err);
        return true;
    }

    bool has_ior(const std::string& material) const { return with_ior_.count(material) > 0; }

private:
    void check_ior(const std::string& text, const std::string& path) {
        std::istringstream lines(text);
        std::string line, material;
        for (int number = 1; std::getline(lines, line); ++number) {
            std::istringstream fields(line);
            std::string keyword, value, extra;
            fields >> keyword;
            if (keyword == "newmtl") fields >> material;
            if (keyword != "Ni") continue;
            fields >> value;
            char* end = nullptr;
            double ior = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || (fields >> extra) || !std::isfinite(ior) || ior < 0)
                throw InputError(where_ + ": " + path + ": line " + std::to_string(number) + ": Ni (index of refraction of '" +
                                 material + "') must be a finite number >= 0, got '" + value + "'");
            with_ior_.insert(material);
        }
    }

    std::string directory_, where_;
    std::set<std::string> with_ior_;
};

std::string base_name(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// Image textures of one OBJ's materials, by file: one load per file.
using TextureCache = std::map<std::string, std::shared_ptr<const Texture>>;

Material to_material(const tinyobj::material_t& m, const std::string& prefix, bool has_ior,
                     const std::string& directory, const std::string& where, TextureCache& textures) {
    Material mat;
    mat.name = prefix + m.name;
    mat.albedo = Color(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    if (!m.diffuse_texname.empty()) {
        // map_Kd: the diffuse albedo from an image; its "-s u v w" option scales (u, v).
        std::string file = m.diffuse_texname[0] == '/' ? m.diffuse_texname : directory + m.diffuse_texname;
        Vec2 scale(m.diffuse_texopt.scale[0], m.diffuse_texopt.scale[1]);
        if (!(scale.x > 0 && scale.y > 0))
            throw InputError(where + ": material '" + m.name + "': map_Kd -s must be > 0");
        std::string key = file + " " + std::to_string(scale.x) + " " + std::to_string(scale.y);
        auto it = textures.find(key);
        if (it == textures.end())
            it = textures.emplace(key, load_albedo_texture(file, where + ": material '" + m.name + "': map_Kd", scale)).first;
        mat.albedo_texture = it->second;
    }
    mat.emission = Color(m.emission[0], m.emission[1], m.emission[2]);
    if (m.illum == 3 || m.illum == 5) {
        mat.type = MaterialType::mirror;
        mat.reflectance = Color(m.specular[0], m.specular[1], m.specular[2]);
    } else if (m.illum == 4 || m.illum == 6 || m.illum == 7) {
        // Glass; with the PBR extension's roughness Pr > 0, rough glass of GGX alpha Pr.
        mat.type = m.roughness > 0 ? MaterialType::rough_dielectric : MaterialType::glass;
        mat.roughness = std::clamp(double(m.roughness), ggx::kMinAlpha, 1.0);
        // Without Ni, glass is 1.5 (tinyobjloader would say 1, which is no glass at all).
        mat.ior = has_ior ? m.ior : 1.5;
        if (!(mat.ior > 0))
            throw InputError(where + ": material '" + m.name + "': glass (illum " + std::to_string(m.illum) +
                             ") needs Ni > 0, got " + std::to_string(m.ior));
    } else if (m.metallic > 0) {
        // The PBR extension of MTL: Pm (metallic) > 0 makes a rough metal
        // whose colour at normal incidence is Kd and whose GGX alpha is Pr.
        mat.type = MaterialType::microfacet;
        mat.roughness = std::clamp(double(m.roughness), ggx::kMinAlpha, 1.0);
        ConductorIndex index = conductor_from_reflectance(mat.albedo);
        mat.eta = index.eta;
        mat.k = index.k;
    }
    return mat;
}

void check_material(const Material& m, const std::string& where) {
    auto in_unit = [](const Color& c) { return c.r >= 0 && c.g >= 0 && c.b >= 0 && c.r <= 1 && c.g <= 1 && c.b <= 1; };
    if (!m.albedo.is_finite() || !in_unit(m.albedo))
        throw InputError(where + ": material '" + m.name + "': Kd must lie in [0, 1]");
    if (!m.emission.is_finite() || m.emission.r < 0 || m.emission.g < 0 || m.emission.b < 0)
        throw InputError(where + ": material '" + m.name + "': Ke must be finite and >= 0");
    if (!in_unit(m.reflectance)) throw InputError(where + ": material '" + m.name + "': Ks must lie in [0, 1]");
}

}  // namespace

MeshData read_obj(Scene& scene, const std::string& path, const ObjLoadOptions& options) {
    const std::string where = options.where.empty() ? path : options.where + " (" + path + ")";
    require_readable_file(path, options.where.empty() ? std::string("mesh") : options.where);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    ObjCounts counts = scan_obj(path, where);
    check_geometry_budget(scene.triangles.size() + counts.triangles, scene.positions.size() + counts.vertices, where);
    std::ifstream obj(path, std::ios::binary);
    CheckedMaterialReader mtl_reader(directory_of(path), where);
    bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &obj, &mtl_reader, /*triangulate=*/true);
    if (!ok) throw InputError(where + ": not a readable OBJ file: " + (err.empty() ? warn : err));
    // tinyobjloader only warns about a missing material library; a scene
    // whose colours silently vanish is worse than an error.
    if (warn.find("not found") != std::string::npos || err.find("not found") != std::string::npos)
        throw InputError(where + ": " + (warn.empty() ? err : warn));

    MeshData mesh;
    const size_t vertex_count = attrib.vertices.size() / 3;
    const size_t normal_count = attrib.normals.size() / 3;
    for (size_t i = 0; i < vertex_count; ++i) {
        Vec3 p(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
        if (!p.is_finite()) throw InputError(where + ": vertex " + std::to_string(i + 1) + " is not finite");
        mesh.positions.push_back(p);
    }
    for (size_t i = 0; i < normal_count; ++i) {
        Vec3 n(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]);
        if (!n.is_finite()) throw InputError(where + ": normal " + std::to_string(i + 1) + " is not finite");
        // A zero normal cannot be normalised; the intersection falls back to
        // the geometric normal when interpolation yields zero anyway.
        mesh.normals.push_back(n.norm() > 0 ? n.unit() : n);
    }

    // The MTL's materials become scene materials named "mesh.obj:name".
    std::vector<uint32_t> scene_material(materials.size());
    TextureCache textures;
    if (!options.material) {
        for (size_t m = 0; m < materials.size(); ++m) {
            Material mat = to_material(materials[m], base_name(path) + ":", mtl_reader.has_ior(materials[m].name),
                                       directory_of(path), where, textures);
            check_material(mat, where);
            scene_material[m] = uint32_t(scene.materials.size());
            scene.materials.push_back(mat);
        }
    }

    const size_t uv_count = attrib.texcoords.size() / 2;
    for (size_t i = 0; i < uv_count; ++i) mesh.uvs.push_back(Vec2(attrib.texcoords[2 * i], attrib.texcoords[2 * i + 1]));
    bool any_uv = false;

    bool all_smooth = normal_count > 0;
    std::vector<std::array<uint32_t, 3>> face_normals;
    for (const tinyobj::shape_t& shape : shapes) {
        const std::vector<tinyobj::index_t>& idx = shape.mesh.indices;
        for (size_t f = 0; f + 2 < idx.size(); f += 3) {
            std::array<uint32_t, 3> face, normals, uvs;
            bool has_uv = true;
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& c = idx[f + k];
                if (c.vertex_index < 0 || size_t(c.vertex_index) >= vertex_count)
                    throw InputError(where + ": face in '" + shape.name + "' uses vertex " +
                                     std::to_string(c.vertex_index + 1) + " but the file has " +
                                     std::to_string(vertex_count));
                if (c.normal_index >= 0 && size_t(c.normal_index) >= normal_count)
                    throw InputError(where + ": face in '" + shape.name + "' uses normal " +
                                     std::to_string(c.normal_index + 1) + " but the file has " +
                                     std::to_string(normal_count));
                if (c.texcoord_index >= 0 && size_t(c.texcoord_index) >= uv_count)
                    throw InputError(where + ": face in '" + shape.name + "' uses texture coordinate " +
                                     std::to_string(c.texcoord_index + 1) + " but the file has " +
                                     std::to_string(uv_count));
                uvs[k] = c.texcoord_index >= 0 ? uint32_t(c.texcoord_index) : kNoIndex;
                has_uv = has_uv && c.texcoord_index >= 0;
                face[k] = uint32_t(c.vertex_index);
                normals[k] = c.normal_index >= 0 ? uint32_t(c.normal_index) : kNoIndex;
                if (c.normal_index < 0) all_smooth = false;
            }
            mesh.faces.push_back(face);
            face_normals.push_back(normals);
            mesh.face_uvs.push_back(has_uv ? uvs : std::array<uint32_t, 3>{kNoIndex, kNoIndex, kNoIndex});
            any_uv = any_uv || has_uv;

            int material_id = shape.mesh.material_ids.empty() ? -1 : shape.mesh.material_ids[f / 3];
            uint32_t m;
            if (options.material) {
                m = *options.material;
            } else if (material_id >= 0 && size_t(material_id) < materials.size()) {
                m = scene_material[material_id];
            } else if (options.fallback_material) {
                m = *options.fallback_material;
            } else {
                throw InputError(where + ": faces of '" + shape.name +
                                 "' have no material: give the object a \"material\" or the OBJ an MTL file");
            }
            mesh.face_materials.push_back(m);
        }
    }
    if (mesh.faces.empty()) throw InputError(where + ": the mesh has no faces");
    // Smooth shading only when every corner has a normal; a mix would need
    // per-face bookkeeping that no test mesh needs.
    if (!any_uv) {
        mesh.uvs.clear();
        mesh.face_uvs.clear();
    }
    if (all_smooth) mesh.face_normals = std::move(face_normals);
    else mesh.normals.clear();
    return mesh;
}

}  // namespace pt
