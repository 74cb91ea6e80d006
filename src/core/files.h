// Small file-system checks shared by the loaders and the apps.
#pragma once

#include <cstdint>
#include <string>

namespace pt {

/// Throws InputError "<where>: cannot read <path>: <reason>" unless `path`
/// is a readable regular file (a device such as /dev/zero would never end).
void require_readable_file(const std::string& path, const std::string& where);

/// The whole of a small file: require_readable_file, then a size check
/// before anything is read (a 2 GB "scene" must not take 4 GB of memory to
/// be refused). Throws InputError "<where>: <path> is N bytes; <what> is at
/// most M bytes".
std::string read_small_file(const std::string& path, const std::string& where, uint64_t max_bytes,
                            const std::string& what);

/// The directory part of a path with its trailing slash ("a/b/c.obj" ->
/// "a/b/"), or "" for a bare file name.
std::string directory_of(const std::string& path);

}  // namespace pt
