#include "scene/scene_loader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/files.h"
#include "core/math.h"
#include "core/memory_budget.h"
#include "image/image_io.h"
#include "scene/csg.h"
#include "scene/framing.h"
#include "scene/fresnel.h"
#include "scene/json_reader.h"
#include "scene/mesh.h"
#include "scene/microfacet.h"
#include "scene/obj_loader.h"
#include "scene/texture.h"
#include "scene/density_grid.h"
#include "scene/medium_boundary.h"

namespace pt {
namespace {

/// Limits that keep a typo from asking for terabytes (geometry: core/memory_budget.h).
constexpr int kMaxFilmPixels = 1 << 26;          // e.g. 8192 x 8192

std::string resolve(const std::string& scene_path, const std::string& file) {
    if (!file.empty() && file[0] == '/') return file;
    return directory_of(scene_path) + file;
}

std::string stem(const std::string& path) {
    size_t slash = path.find_last_of('/');
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    size_t dot = name.find_last_of('.');
    return dot == std::string::npos ? name : name.substr(0, dot);
}

/// A scene is a few kilobytes of JSON; its meshes are separate OBJ files.
constexpr uint64_t kMaxSceneBytes = 64 << 20;

std::string read_text(const std::string& path) {
    return read_small_file(path, "scene", kMaxSceneBytes, "a scene file (meshes go in OBJ files)");
}

void read_camera(Scene& scene, const JsonReader& j) {
    Camera& c = scene.camera;
    std::string type = j.has("type") ? j.string("type") : "perspective";
    // Each type has its own keys; a key of another type is an error, not ignored.
    if (type == "perspective") {
        c.type = CameraType::perspective;
        j.allow_only({"type", "position", "look_at", "up", "vfov", "lens_radius", "focal_distance", "near_clip", "far_clip"});
    } else if (type == "orthographic") {
        c.type = CameraType::orthographic;
        j.allow_only({"type", "position", "look_at", "up", "height", "near_clip", "far_clip"});
        if (!j.has("height")) j.fail("height", "an orthographic camera needs \"height\" (the view height in scene units)");
        c.height = j.positive("height");
    } else if (type == "fisheye") {
        c.type = CameraType::fisheye;
        j.allow_only({"type", "position", "look_at", "up", "fov", "near_clip", "far_clip"});
        c.fov = j.number_in("fov", 1e-6, 360, 180);
    } else {
        j.fail("type", "unknown camera type \"" + type + "\" (expected perspective, orthographic or fisheye)");
    }
    c.position = j.vec3("position");
    c.look_at = j.vec3("look_at");
    c.up = j.vec3("up", Vec3(0, 1, 0));
    if (!(c.up.norm() > 0)) j.fail("up", "expected a non-zero vector");
    c.vfov = j.number("vfov", 45.0);
    if (!(c.vfov > 0 && c.vfov < 180)) j.fail("vfov", "expected an angle in (0, 180) degrees");
    c.lens_radius = j.number_in("lens_radius", 0, 1e300, 0);
    c.focal_distance = j.number_in("focal_distance", 0, 1e300, 0);
    c.near_clip = j.number_in("near_clip", 0, 1e300, 0);
    c.far_clip = j.number_in("far_clip", 0, 1e300, 1e300);
    if (c.far_clip <= c.near_clip) j.fail("far_clip", "expected far_clip > near_clip");
}

/// A texture's (u, v) multiplier: a number, or [su, sv]; 1 by default.
Vec2 read_uv_scale(const JsonReader& j) {
    if (!j.has("scale")) return Vec2(1, 1);
    if (!j.is_array("scale")) {
        double s = j.positive("scale");
        return Vec2(s, s);
    }
    std::vector<double> s = j.numbers("scale", 2);
    if (!(s[0] > 0 && s[1] > 0)) j.fail("scale", "expected a number > 0 or two numbers > 0");
    return Vec2(s[0], s[1]);
}

/// A diffuse albedo given as a texture (scene/texture.h):
///   {"texture": "file.png", "scale": s}  or
///   {"checkerboard": {"even": [r, g, b], "odd": [r, g, b]}, "scale": s}.
std::shared_ptr<const Texture> read_albedo_texture(const JsonReader& j, const std::string& scene_path) {
    j.allow_only({"texture", "checkerboard", "scale"});
    Vec2 scale = read_uv_scale(j);
    if (j.has("texture") == j.has("checkerboard"))
        j.fail("", "expected either \"texture\" (an image file) or \"checkerboard\" (two colours)");
    if (j.has("texture"))
        return load_albedo_texture(resolve(scene_path, j.string("texture")), j.file() + ": " + j.path_of("texture"),
                                   scale);
    JsonReader board = j.object("checkerboard");
    board.allow_only({"even", "odd"});
    if (!board.has("even") || !board.has("odd")) board.fail("", "expected \"even\" and \"odd\" colours");
    return std::make_shared<const CheckerboardTexture>(board.color("even", Color(0), 1.0), board.color("odd", Color(0), 1.0),
                                                       scale);
}

/// The facets of a rough material: "distribution" (ggx, beckmann or
/// blinn_phong), "roughness" alpha or [alpha_x, alpha_y] (anisotropic; GGX
/// and Beckmann), or "exponent" (Blinn-Phong).
void read_microfacet(const JsonReader& j, Material& m) {
    std::string d = j.has("distribution") ? j.string("distribution") : "ggx";
    if (d == "ggx") m.distribution = MicrofacetModel::ggx;
    else if (d == "beckmann") m.distribution = MicrofacetModel::beckmann;
    else if (d == "blinn_phong") m.distribution = MicrofacetModel::blinn_phong;
    else j.fail("distribution", "unknown distribution \"" + d + "\" (expected ggx, beckmann or blinn_phong)");
    if (m.distribution == MicrofacetModel::blinn_phong) {
        if (j.has("roughness")) j.fail("roughness", "the blinn_phong distribution takes \"exponent\", not \"roughness\"");
        m.exponent = j.number_in("exponent", 0, 1e6, m.exponent);
        return;
    }
    if (j.has("exponent")) j.fail("exponent", "only the blinn_phong distribution takes an \"exponent\"");
    if (j.has("roughness") && j.is_array("roughness")) {
        std::vector<double> a = j.numbers("roughness", 2);
        for (double v : a)
            if (!(v >= ggx::kMinAlpha && v <= 1.0))
                j.fail("roughness", "expected alpha or [alpha_x, alpha_y], each in [0.001, 1]");
        m.roughness = a[0];
        m.roughness_y = a[1];
    } else {
        m.roughness = j.number_in("roughness", ggx::kMinAlpha, 1.0, m.roughness);
    }
}

/// A participating medium (scene/medium.h): {"sigma_a": [r, g, b],
/// "sigma_s": [r, g, b], "g": 0, "density": "file.grid"}; coefficients per
/// scene unit, >= 0; g in (-1, 1); the density grid optional.
Medium read_medium(const std::string& name, const JsonReader& j, const std::string& scene_path) {
    j.allow_only({"sigma_a", "sigma_s", "g", "density"});
    if (!j.has("sigma_a") && !j.has("sigma_s"))
        j.fail("", "a medium needs \"sigma_a\" and/or \"sigma_s\" (per scene unit)");
    Medium m;
    m.name = name;
    m.sigma_a = j.color("sigma_a", Color(0));
    m.sigma_s = j.color("sigma_s", Color(0));
    m.g = j.number("g", 0.0);
    if (!(m.g > -1.0 && m.g < 1.0)) {
        std::ostringstream s;
        s << "expected the Henyey-Greenstein g in (-1, 1), got " << m.g;
        j.fail("g", s.str());
    }
    if (j.has("density"))
        m.density = std::make_shared<const DensityGrid>(
            load_density_grid(resolve(scene_path, j.string("density")), j.file() + ": " + j.path_of("density")));
    return m;
}

Material read_material(const std::string& name, const JsonReader& j, const std::string& scene_path, Scene& scene) {
    Material m;
    m.name = name;
    std::string type = j.string("type");
    if (j.has("interior")) {
        if (type != "null" && type != "transparent" && type != "glass" && type != "rough_dielectric")
            j.fail("interior", "a medium needs a boundary that light can cross: material type null, glass or "
                               "rough_dielectric, not " + type);
        m.interior = int(scene.media.size());
        scene.media.push_back(read_medium(name, j.object("interior"), scene_path));
    }
    if (type == "null" || type == "transparent") {
        j.allow_only({"type", "interior"});
        m.type = MaterialType::null;
    } else if (type == "diffuse") {
        j.allow_only({"type", "albedo", "emission"});
        m.type = MaterialType::diffuse;
        if (j.has("albedo") && !j.is_array("albedo")) m.albedo_texture = read_albedo_texture(j.object("albedo"), scene_path);
        else m.albedo = j.color("albedo", m.albedo, 1.0);
    } else if (type == "mirror") {
        j.allow_only({"type", "reflectance", "emission"});
        m.type = MaterialType::mirror;
        m.reflectance = j.color("reflectance", m.reflectance, 1.0);
    } else if (type == "glass") {
        j.allow_only({"type", "ior", "reflectance", "transmittance", "emission", "interior"});
        m.type = MaterialType::glass;
        m.ior = j.positive("ior", 1.5);
        m.reflectance = j.color("reflectance", m.reflectance, 1.0);
        m.transmittance = j.color("transmittance", m.transmittance, 1.0);
    } else if (type == "microfacet") {
        j.allow_only({"type", "roughness", "distribution", "exponent", "eta", "k", "reflectance", "emission"});
        m.type = MaterialType::microfacet;
        read_microfacet(j, m);
        // A metal is given by its complex index (eta and k together) or by
        // its colour at normal incidence ("reflectance"), never both.
        bool has_index = j.has("eta") || j.has("k");
        if (has_index && j.has("reflectance"))
            j.fail("reflectance", "give either \"eta\" and \"k\" or \"reflectance\", not both");
        if (has_index) {
            if (!j.has("eta")) j.fail("eta", "expected \"eta\" together with \"k\"");
            if (!j.has("k")) j.fail("k", "expected \"k\" together with \"eta\"");
            m.eta = j.color("eta", m.eta);
            m.k = j.color("k", m.k);
            if (!(m.eta.r > 0 && m.eta.g > 0 && m.eta.b > 0))
                j.fail("eta", "expected three numbers > 0");
        } else if (j.has("reflectance")) {
            ConductorIndex index = conductor_from_reflectance(j.color("reflectance", Color(0), 1.0));
            m.eta = index.eta;
            m.k = index.k;
        } else {
            j.fail("", "a microfacet material needs \"eta\" and \"k\" (the metal's complex index) or "
                       "\"reflectance\" (its colour)");
        }
    } else if (type == "rough_dielectric") {
        j.allow_only({"type", "ior", "roughness", "distribution", "exponent", "reflectance", "transmittance", "emission",
                      "interior"});
        m.type = MaterialType::rough_dielectric;
        m.ior = j.positive("ior", 1.5);
        read_microfacet(j, m);
        m.reflectance = j.color("reflectance", m.reflectance, 1.0);
        m.transmittance = j.color("transmittance", m.transmittance, 1.0);
    } else {
        j.fail("type", "unknown material type \"" + type +
                           "\" (expected diffuse, mirror, glass, microfacet, rough_dielectric or null)");
    }
    m.emission = j.color("emission", Color(0));
    return m;
}

Transform read_transform(const JsonReader& j) {
    j.allow_only({"scale", "rotate", "translate"});
    Transform t;
    if (j.has("scale")) {
        // A number scales uniformly; three numbers scale per axis.
        if (j.is_array("scale")) {
            t.scale = j.vec3("scale");
            if (!(t.scale.x > 0 && t.scale.y > 0 && t.scale.z > 0))
                j.fail("scale", "expected a number > 0 or three numbers > 0");
        } else {
            t.scale = Vec3(j.positive("scale"));
        }
    }
    if (j.has("rotate")) {
        std::vector<double> r = j.numbers("rotate", 4);
        Vec3 axis(r[0], r[1], r[2]);
        if (!(axis.norm() > 0)) j.fail("rotate", "expected [x, y, z, degrees] with a non-zero axis");
        t.set_rotation(axis, r[3]);
    }
    t.translate = j.vec3("translate", Vec3(0));
    return t;
}

class SceneBuilder {
public:
    SceneBuilder(Scene& scene, const std::string& path) : scene_(scene), path_(path) {}

    void read_materials(const JsonReader& root) {
        if (!root.has("materials")) return;
        for (const auto& [name, j] : root.object_map("materials")) {
            material_index_[name] = uint32_t(scene_.materials.size());
            scene_.materials.push_back(read_material(name, j, path_, scene_));
        }
    }

    uint32_t material(const JsonReader& j) const {
        std::string name = j.string("material");
        auto it = material_index_.find(name);
        if (it == material_index_.end()) j.fail("material", "no material named \"" + name + "\" in \"materials\"");
        return it->second;
    }

    void read_object(const JsonReader& j) {
        std::string type = j.string("type");
        if (type == "instance") return read_instance(j);
        if (type == "csg") return read_csg_object(j);
        Transform transform = j.has("transform") ? read_transform(j.object("transform")) : Transform();
        if (type == "mesh") {
            j.allow_only({"type", "file", "material", "transform"});
            ObjLoadOptions options;
            options.where = j.file() + ": " + j.path_of("");
            if (j.has("material")) options.material = material(j);
            MeshData mesh = read_obj(scene_, resolve(path_, j.string("file")), options);
            add_boundary_mesh(j, mesh, transform);
        } else if (type == "sphere") {
            j.allow_only({"type", "center", "radius", "material", "transform"});
            if (!transform.is_uniform_scale()) j.fail("transform", "a sphere needs a uniform scale");
            SphereRecord s;
            s.sphere.center = transform.point(j.vec3("center"));
            s.sphere.radius = j.positive("radius") * transform.scale.x;
            s.material = material(j);
            scene_.spheres.push_back(s);
        } else if (type == "quad") {
            j.allow_only({"type", "corner", "edge1", "edge2", "material", "transform"});
            Vec3 c = j.vec3("corner"), e1 = j.vec3("edge1"), e2 = j.vec3("edge2");
            if (!(cross(e1, e2).norm() > 1e-12 * e1.norm() * e2.norm()))
                j.fail("", "zero-area quad (edge1 and edge2 must be non-zero and not parallel)");
            // Two triangles whose geometric normals are both edge1 x edge2.
            MeshData mesh;
            mesh.positions = {c, c + e1, c + e1 + e2, c + e2};
            mesh.faces = {{0, 1, 2}, {0, 2, 3}};
            mesh.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};  // (u, v) along (edge1, edge2)
            mesh.face_uvs = {{0, 1, 2}, {0, 2, 3}};
            mesh.material = material(j);
            add_boundary_mesh(j, mesh, transform);
        } else if (type == "torus_knot") {
            j.allow_only({"type", "p", "q", "radius", "tube_radius", "segments", "sides", "material", "transform"});
            int segments = j.integer("segments", 3, 1 << 22, 500), sides = j.integer("sides", 3, 1 << 16, 10);
            check_geometry_budget(scene_.triangles.size() + 2 * uint64_t(segments) * uint64_t(sides),
                                  scene_.positions.size() + uint64_t(segments) * uint64_t(sides),
                                  j.file() + ": " + j.path_of("") + " (2 * segments * sides)");
            MeshData mesh = make_torus_knot(j.integer("p", 1, 64, 2), j.integer("q", 1, 64, 3),
                                            j.positive("radius", 1.0), j.positive("tube_radius", 0.15), segments, sides);
            mesh.material = material(j);
            add_boundary_mesh(j, mesh, transform);
        } else {
            j.fail("type", "unknown object type \"" + type + "\" (expected mesh, sphere, quad, torus_knot, instance or csg)");
        }
    }

    /// The "shapes" table: NAME -> a mesh, torus knot or sphere in object
    /// space, without a material (its instances give one).
    void read_shapes(const JsonReader& root) {
        if (!root.has("shapes")) return;
        for (const auto& [name, j] : root.object_map("shapes")) {
            if (j.string("type") == "group") {  // placed member by member (place_group)
                j.allow_only({"type", "objects"});
                groups_.emplace(name, j);
                continue;
            }
            auto shape = std::make_shared<Scene>();
            shape->path = path_;
            shape->materials.push_back(Material{});  // placeholder: instances bring their own
            std::shared_ptr<const CsgTree> csg;
            std::string type = j.string("type");
            if (type == "mesh") {
                j.allow_only({"type", "file", "transform"});
                ObjLoadOptions options;
                options.where = j.file() + ": " + j.path_of("");
                options.material = 0;
                add_mesh(*shape, read_obj(*shape, resolve(path_, j.string("file")), options), read_shape_transform(j));
            } else if (type == "torus_knot") {
                j.allow_only({"type", "p", "q", "radius", "tube_radius", "segments", "sides", "transform"});
                int segments = j.integer("segments", 3, 1 << 22, 500), sides = j.integer("sides", 3, 1 << 16, 10);
                check_geometry_budget(2 * uint64_t(segments) * uint64_t(sides), uint64_t(segments) * uint64_t(sides),
                                      j.file() + ": " + j.path_of("") + " (2 * segments * sides)");
                MeshData mesh = make_torus_knot(j.integer("p", 1, 64, 2), j.integer("q", 1, 64, 3),
                                                j.positive("radius", 1.0), j.positive("tube_radius", 0.15), segments, sides);
                mesh.material = 0;
                add_mesh(*shape, mesh, read_shape_transform(j));
            } else if (type == "sphere") {
                j.allow_only({"type", "center", "radius"});
                shape->spheres.push_back({{j.vec3("center", Vec3(0)), j.positive("radius", 1.0)}, 0});
            } else if (type == "csg") {
                j.allow_only({"type", "op", "operands"});
                auto tree = std::make_shared<CsgTree>();
                read_csg_node(j, *shape, *tree, false, 0);
                csg = tree;
            } else {
                j.fail("type", "unknown shape type \"" + type + "\" (expected mesh, torus_knot, sphere, csg or group)");
            }
            shape->finalize();
            shape_index_[name] = uint32_t(scene_.shapes.size());
            scene_.shapes.push_back({name, shape, csg});
        }
        // Every group is checked here, placed or not: unknown names, cycles,
        // transforms that cannot be composed, the instance count.
        for (const auto& [name, j] : groups_) {
            std::vector<std::string> chain;
            place_group(name, j, Transform(), chain, false);
        }
    }

    /// {"type": "instance", "shape": NAME, "transform": {...}, "material": M}.
    void read_instance(const JsonReader& j) {
        j.allow_only({"type", "shape", "transform", "material"});
        std::string name = j.string("shape");
        if (groups_.count(name)) {
            if (j.has("material"))
                j.fail("material", "an instance of the group \"" + name + "\" takes no material: its members bring theirs");
            Transform t = j.has("transform") ? read_transform(j.object("transform")) : Transform();
            std::vector<std::string> chain;
            place_group(name, groups_.at(name), t, chain, true);
            return;
        }
        auto it = shape_index_.find(name);
        if (it == shape_index_.end()) j.fail("shape", "no shape named \"" + name + "\" in \"shapes\"");
        place_instance(j, it->second, "an instance");
    }

    /// A group ({"type": "group", "objects": [instances]}) seen through
    /// `outer`: every member's transform composed with it, a member that is
    /// itself a group recursively. Nested instances are flattened here into
    /// one InstanceRecord per placed leaf shape (geometry still stored once;
    /// the accelerator keeps two levels). `place` false only checks.
    void place_group(const std::string& name, const JsonReader& group, const Transform& outer,
                     std::vector<std::string>& chain, bool place) {
        if (std::find(chain.begin(), chain.end(), name) != chain.end()) {
            std::string cycle;
            for (const std::string& c : chain) cycle += c + " -> ";
            group.fail("", "groups place each other in a cycle: " + cycle + name);
        }
        constexpr size_t kMaxGroupDepth = 16;
        if (chain.size() >= kMaxGroupDepth)
            group.fail("", "groups nested more than " + std::to_string(kMaxGroupDepth) + " deep");
        chain.push_back(name);
        for (const JsonReader& member : group.object_array("objects")) {
            member.allow_only({"type", "shape", "transform", "material"});
            if (member.string("type") != "instance")
                member.fail("type", "a group holds instances only, got \"" + member.string("type") + "\"");
            Transform inner = member.has("transform") ? read_transform(member.object("transform")) : Transform();
            Transform composed = compose(outer, inner, member);
            std::string shape = member.string("shape");
            auto sub = groups_.find(shape);
            if (sub != groups_.end()) {
                if (member.has("material"))
                    member.fail("material", "an instance of the group \"" + shape + "\" takes no material: its members bring theirs");
                place_group(shape, sub->second, composed, chain, place);
                continue;
            }
            auto it = shape_index_.find(shape);
            if (it == shape_index_.end()) member.fail("shape", "no shape named \"" + shape + "\" in \"shapes\"");
            uint32_t m = material(member);
            const bool emits = scene_.materials[m].is_emissive();
            if (emits && scene_.shapes[it->second].csg)
                member.fail("material", "an instance cannot emit light (a CSG solid is not sampled as a light)");
            if (!place) continue;
            if (emits) {
                expand_emitting_instance(member, it->second, m, composed);
                continue;
            }
            constexpr size_t kMaxInstances = 16u << 20;
            if (scene_.instances.size() >= kMaxInstances)
                member.fail("", "the groups place more than " + std::to_string(kMaxInstances) +
                                    " instances (about 180 bytes each once flattened)");
            add_instance(it->second, m, composed);
        }
        chain.pop_back();
    }

    /// outer after inner. The scene's transforms are R S + T with R a
    /// rotation and S diagonal; R1 S1 R2 S2 is of that form when S1 is
    /// uniform ((R1 R2)(s1 S2)) or R2 is the identity (R1 (S1 S2)), and a
    /// shear otherwise, which the renderer's transforms cannot hold.
    static Transform compose(const Transform& outer, const Transform& inner, const JsonReader& where) {
        const bool inner_unrotated = inner.rows[0] == Vec3(1, 0, 0) && inner.rows[1] == Vec3(0, 1, 0) &&
                                     inner.rows[2] == Vec3(0, 0, 1);
        if (!outer.is_uniform_scale() && !inner_unrotated)
            where.fail("transform", "a rotated member of a group placed with a non-uniform scale would be sheared; "
                                    "scale the group uniformly, or scale the member itself");
        Transform t;
        t.scale = outer.scale * inner.scale;
        for (int r = 0; r < 3; ++r)
            t.rows[r] = Vec3(dot(outer.rows[r], Vec3(inner.rows[0].x, inner.rows[1].x, inner.rows[2].x)),
                             dot(outer.rows[r], Vec3(inner.rows[0].y, inner.rows[1].y, inner.rows[2].y)),
                             dot(outer.rows[r], Vec3(inner.rows[0].z, inner.rows[1].z, inner.rows[2].z)));
        t.translate = outer.point(inner.translate);
        return t;
    }

    /// {"type": "csg", "op": ..., "operands": [...], "material": M,
    /// "transform": {...}}: a CSG shape of its own, placed as an instance
    /// (its rays go into the tree's space by the inverse transform).
    void read_csg_object(const JsonReader& j) {
        j.allow_only({"type", "op", "operands", "material", "transform"});
        auto shape = std::make_shared<Scene>();
        shape->path = path_;
        shape->materials.push_back(Material{});
        auto tree = std::make_shared<CsgTree>();
        read_csg_node(j, *shape, *tree, false, 0);
        shape->finalize();
        scene_.shapes.push_back({j.path_of(""), shape, tree});
        place_instance(j, uint32_t(scene_.shapes.size() - 1), "a CSG object");
    }

    /// One node of a CSG tree and its subtree: {"type": "csg", "op",
    /// "operands"}, or a leaf: {"type": "sphere", "center", "radius"} or
    /// {"type": "mesh", "file", "transform"} (closed). `inverted`: the node is
    /// subtracted an odd number of times, so its leaves are stored turned
    /// round (scene/csg.h). Returns the node's index.
    uint32_t read_csg_node(const JsonReader& j, Scene& shape, CsgTree& tree, bool inverted, int depth) {
        constexpr int kMaxCsgDepth = 32;
        if (depth > kMaxCsgDepth) j.fail("", "CSG nested more than " + std::to_string(kMaxCsgDepth) + " levels deep");
        const uint32_t index = uint32_t(tree.nodes.size());
        tree.nodes.emplace_back();
        CsgNode node;
        node.inverted = inverted;
        std::string type = j.string("type");
        if (type == "csg") {
            if (depth > 0) j.allow_only({"type", "op", "operands"});
            std::string op = j.string("op");
            if (!parse_csg_op(op, node.op))
                j.fail("op", "expected \"union\", \"intersection\" or \"difference\", got \"" + op + "\"");
            std::vector<JsonReader> operands = j.object_array("operands");
            if (operands.size() < 2)
                j.fail("operands", "expected at least two operands, got " + std::to_string(operands.size()));
            for (size_t k = 0; k < operands.size(); ++k) {
                // The subtracted operands of a difference face the other way.
                bool flip = node.op == CsgOp::difference && k > 0;
                node.children.push_back(read_csg_node(operands[k], shape, tree, inverted != flip, depth + 1));
            }
        } else if (type == "sphere") {
            j.allow_only({"type", "center", "radius"});
            SphereRecord sphere{{j.vec3("center"), j.positive("radius")}, 0, inverted};
            node.sphere = true;
            node.first = uint32_t(shape.spheres.size());
            node.count = 1;
            shape.spheres.push_back(sphere);
        } else if (type == "mesh") {
            j.allow_only({"type", "file", "transform"});
            ObjLoadOptions options;
            options.where = j.file() + ": " + j.path_of("");
            options.material = 0;
            MeshData mesh = read_obj(shape, resolve(path_, j.string("file")), options);
            std::string problem = orient_closed_mesh(mesh, "a CSG operand must be a closed, consistently wound mesh, but ");
            if (!problem.empty()) j.fail("", problem);
            if (inverted) {
                for (size_t f = 0; f < mesh.faces.size(); ++f) {
                    std::swap(mesh.faces[f][1], mesh.faces[f][2]);
                    if (!mesh.face_normals.empty()) std::swap(mesh.face_normals[f][1], mesh.face_normals[f][2]);
                    if (!mesh.face_uvs.empty()) std::swap(mesh.face_uvs[f][1], mesh.face_uvs[f][2]);
                }
                for (Vec3& n : mesh.normals) n = -n;
            }
            node.first = uint32_t(shape.triangles.size());
            add_mesh(shape, mesh, read_shape_transform(j));
            node.count = uint32_t(shape.triangles.size()) - node.first;
        } else {
            j.fail("type", "unknown CSG operand type \"" + type + "\" (expected sphere, mesh or csg)");
        }
        tree.nodes[index] = node;
        return index;
    }

    /// An instance of shape `shape_index` with the object's material and
    /// transform (`what` names the object in errors).
    void place_instance(const JsonReader& j, uint32_t shape_index, const std::string& what) {
        InstanceRecord instance;
        instance.shape = shape_index;
        instance.material = material(j);
        Transform to_world = j.has("transform") ? read_transform(j.object("transform")) : Transform();
        if (scene_.materials[instance.material].is_emissive()) {
            if (scene_.shapes[shape_index].csg) j.fail("material", what + " cannot emit light (a CSG solid is not sampled as a light)");
            return expand_emitting_instance(j, shape_index, instance.material, to_world);
        }
        add_instance(instance.shape, instance.material, to_world);
    }

    /// An emitting instance: its shape's primitives copied into the world,
    /// transformed, since light sampling (scene/light_set.h) picks world
    /// triangles and spheres by area. Lamps are few and small, so the copy
    /// is cheap where it happens; everything else stays instanced.
    void expand_emitting_instance(const JsonReader& j, uint32_t shape_index, uint32_t material, const Transform& t) {
        const Scene& g = *scene_.shapes[shape_index].geometry;
        if (!g.spheres.empty() && !t.is_uniform_scale())
            j.fail("transform", "an emitting instance of a sphere needs a uniform scale (an ellipsoid is not sampled as a light)");
        for (const SphereRecord& s : g.spheres)
            scene_.spheres.push_back({{t.point(s.sphere.center), s.sphere.radius * t.scale.x}, material});
        if (g.triangles.empty()) return;
        check_geometry_budget(scene_.triangles.size() + g.triangles.size(), scene_.positions.size() + g.positions.size(),
                              j.file() + ": " + j.path_of("") + " (an emitting instance, copied)");
        MeshData mesh;
        mesh.positions = g.positions;
        mesh.normals = g.normals;
        mesh.uvs = g.uvs;
        mesh.material = material;
        const bool smooth = g.triangles[0].n[0] != kNoIndex;  // a mesh is smooth everywhere or nowhere
        for (size_t f = 0; f < g.triangles.size(); ++f) {
            const TriangleRecord& r = g.triangles[f];
            mesh.faces.push_back({r.v[0], r.v[1], r.v[2]});
            if (smooth) mesh.face_normals.push_back({r.n[0], r.n[1], r.n[2]});
            if (!g.triangle_uvs.empty()) mesh.face_uvs.push_back(g.triangle_uvs[f]);
        }
        add_mesh(scene_, mesh, t);
    }

    void add_instance(uint32_t shape, uint32_t material, const Transform& to_world) {
        InstanceRecord instance;
        instance.shape = shape;
        instance.material = material;
        instance.to_world = to_world;
        const BBox& box = scene_.shapes[instance.shape].geometry->bounds;
        for (int corner = 0; corner < 8; ++corner)
            instance.bounds.expand(instance.to_world.point(
                Vec3(corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                     corner & 4 ? box.max.z : box.min.z)));
        scene_.instances.push_back(instance);
    }

    void read_light(const JsonReader& j) {
        std::string type = j.string("type");
        if (type == "point") {
            j.allow_only({"type", "position", "intensity"});
            scene_.point_lights.push_back({j.vec3("position"), j.color("intensity", Color(1))});
        } else if (type == "directional") {
            j.allow_only({"type", "direction", "irradiance"});
            Vec3 d = j.vec3("direction");
            if (!(d.norm() > 0)) j.fail("direction", "expected a non-zero vector");
            scene_.directional_lights.push_back({d.unit(), j.color("irradiance", Color(1))});
        } else if (type == "environment") {
            j.allow_only({"type", "radiance", "file", "scale"});
            if (scene_.environment) j.fail("", "a scene has at most one environment light");
            EnvironmentLight env;
            env.radiance = j.color("radiance", Color(1));
            if (j.has("file")) {
                env.file = resolve(path_, j.string("file"));
                std::string ext = file_extension(env.file);
                if (ext != ".hdr" && ext != ".pfm" && ext != ".exr")
                    j.fail("file", "expected a .hdr, .pfm or .exr lat-long map");
                require_readable_file(env.file, j.file() + ": " + j.path_of("file"));
            }
            env.scale = j.positive("scale", 1.0);
            scene_.environment = env;
        } else {
            j.fail("type", "unknown light type \"" + type + "\" (expected point, directional or environment)");
        }
    }

private:
    /// Adds a mesh; where its material holds a medium, its faces of that
    /// material must enclose it (scene/medium_boundary.h), wound outwards.
    void add_boundary_mesh(const JsonReader& j, MeshData& mesh, const Transform& transform) {
        std::string problem = orient_medium_boundaries(mesh, scene_.materials);
        if (!problem.empty()) j.fail("", problem);
        add_mesh(scene_, mesh, transform);
    }

    Transform read_shape_transform(const JsonReader& j) const {
        return j.has("transform") ? read_transform(j.object("transform")) : Transform();
    }

    Scene& scene_;
    const std::string& path_;
    std::map<std::string, uint32_t> material_index_;
    std::map<std::string, uint32_t> shape_index_;
    std::map<std::string, JsonReader> groups_;  ///< the "group" shapes, placed member by member
};

}  // namespace

Scene parse_json_scene(const std::string& text, const std::string& path) {
    nlohmann::json root_json = parse_json_strictly(text, path);
    JsonReader root(root_json, path, "");
    root.allow_only({"description", "camera", "film", "materials", "shapes", "objects", "lights", "medium"});

    Scene scene;
    scene.path = path;
    scene.name = stem(path);
    if (root.has("description")) root.string("description");
    if (root.has("film")) {
        JsonReader film = root.object("film");
        film.allow_only({"width", "height"});
        scene.film_width = film.integer("width", 1, 1 << 15);
        scene.film_height = film.integer("height", 1, 1 << 15);
        if (double(scene.film_width) * scene.film_height > kMaxFilmPixels)
            film.fail("", "width * height must be at most " + std::to_string(kMaxFilmPixels) + " pixels");
    }
    SceneBuilder builder(scene, path);
    builder.read_materials(root);
    if (root.has("medium")) {
        scene.outside_medium = int(scene.media.size());
        scene.media.push_back(read_medium("medium", root.object("medium"), path));
    }
    builder.read_shapes(root);
    for (const JsonReader& object : root.object_array("objects")) builder.read_object(object);
    if (root.has("lights"))
        for (const JsonReader& light : root.object_array("lights")) builder.read_light(light);
    scene.finalize();

    scene.camera.aspect = double(scene.film_width) / scene.film_height;
    if (root.has("camera")) {
        read_camera(scene, root.object("camera"));
    } else {
        if (!scene.has_geometry()) root.fail("", "a scene without objects needs a \"camera\"");
        frame_camera_on_scene(scene.camera, scene);
    }
    scene.camera.finalize(path + ": camera");
    return scene;
}

Scene load_json_scene(const std::string& path) { return parse_json_scene(read_text(path), path); }

Scene load_obj_scene(const std::string& path) {
    Scene scene;
    scene.path = path;
    scene.name = stem(path);
    // Faces without an MTL material get a neutral grey; with no light in the
    // scene the renderer shows normals anyway (DESIGN.md: no light is added).
    Material grey;
    grey.name = "default";
    scene.materials.push_back(grey);
    ObjLoadOptions options;
    options.fallback_material = 0;
    MeshData mesh = read_obj(scene, path, options);
    add_mesh(scene, mesh, Transform());
    scene.finalize();
    scene.camera.aspect = double(scene.film_width) / scene.film_height;
    frame_camera_on_scene(scene.camera, scene);
    scene.camera.finalize(path + ": camera");
    return scene;
}

Scene load_scene(const std::string& path) {
    std::string ext = file_extension(path);
    if (ext == ".json") return load_json_scene(path);
    if (ext == ".obj") return load_obj_scene(path);
    throw InputError(path + ": unknown scene type '" + ext + "' (expected a .json scene or an .obj mesh)");
}

}  // namespace pt
