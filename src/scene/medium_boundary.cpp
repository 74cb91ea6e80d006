#include "scene/medium_boundary.h"

#include <map>
#include <set>
#include <tuple>
#include <utility>

namespace pt {

namespace {

uint32_t material_of_face(const MeshData& mesh, size_t f) {
    return mesh.face_materials.empty() ? mesh.material : mesh.face_materials[f];
}

/// Checks the faces `faces` of `mesh`; reverses them when wound inwards.
std::string orient_part(MeshData& mesh, const std::vector<size_t>& faces, const std::string& intro) {
    // One id per distinct position, so repeated seam vertices count as one.
    std::map<std::tuple<double, double, double>, uint32_t> welded;
    std::vector<uint32_t> id(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const Vec3& p = mesh.positions[v];
        id[v] = welded.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(welded.size())).first->second;
    }
    // Directed edges: each must appear once, and its reverse once.
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t f : faces)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = id[mesh.faces[f][e]], b = id[mesh.faces[f][(e + 1) % 3]];
            if (a != b) ++directed[{a, b}];
        }
    auto where = [&](std::pair<uint32_t, uint32_t> e) {
        // Name the edge by its corner positions: ids mean nothing to a user.
        Vec3 pa, pb;
        for (const auto& [key, value] : welded) {
            if (value == e.first) pa = Vec3(std::get<0>(key), std::get<1>(key), std::get<2>(key));
            if (value == e.second) pb = Vec3(std::get<0>(key), std::get<1>(key), std::get<2>(key));
        }
        auto str = [](const Vec3& p) {
            return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
        };
        return "the edge " + str(pa) + " - " + str(pb);
    };
    for (const auto& [edge, count] : directed) {
        auto reverse = directed.find({edge.second, edge.first});
        int back = reverse == directed.end() ? 0 : reverse->second;
        if (count > 1 || back > 1)
            return intro + where(edge) + " is shared by more than two triangles, or two of them are wound alike";
        if (back == 0) return intro + where(edge) + " belongs to one triangle only (an open mesh has no inside)";
    }
    // The signed volume (divergence theorem): > 0 when the normals point out.
    double volume = 0;
    for (size_t f : faces) {
        const Vec3 &p0 = mesh.positions[mesh.faces[f][0]], &p1 = mesh.positions[mesh.faces[f][1]],
                   &p2 = mesh.positions[mesh.faces[f][2]];
        volume += dot(p0, cross(p1, p2)) / 6.0;
    }
    if (!(volume != 0)) return intro + "it encloses no volume";
    if (volume < 0)
        for (size_t f : faces) {
            std::swap(mesh.faces[f][1], mesh.faces[f][2]);
            if (!mesh.face_normals.empty()) std::swap(mesh.face_normals[f][1], mesh.face_normals[f][2]);
            if (!mesh.face_uvs.empty()) std::swap(mesh.face_uvs[f][1], mesh.face_uvs[f][2]);
        }
    return "";
}

}  // namespace

std::string orient_medium_boundaries(MeshData& mesh, const std::vector<Material>& materials) {
    std::map<uint32_t, std::vector<size_t>> faces_of;
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
        uint32_t m = material_of_face(mesh, f);
        if (m < materials.size() && materials[m].interior >= 0) faces_of[m].push_back(f);
    }
    for (const auto& [m, faces] : faces_of) {
        std::string problem = orient_part(mesh, faces,
                                          "the material \"" + materials[m].name + "\" has an \"interior\" medium, "
                                          "so its mesh must be closed and consistently wound, but ");
        if (!problem.empty()) return problem;
    }
    return "";
}

std::string orient_closed_mesh(MeshData& mesh, const std::string& intro) {
    std::vector<size_t> faces(mesh.faces.size());
    for (size_t f = 0; f < faces.size(); ++f) faces[f] = f;
    return orient_part(mesh, faces, intro);
}

}  // namespace pt
