// Small file-system checks shared by the loaders and the apps.
#pragma once

#include <string>

namespace pt {

/// Throws InputError "<where>: cannot read <path>: <reason>" unless `path`
/// is a readable regular file (a device such as /dev/zero would never end).
void require_readable_file(const std::string& path, const std::string& where);

/// The directory part of a path with its trailing slash ("a/b/c.obj" ->
/// "a/b/"), or "" for a bare file name.
std::string directory_of(const std::string& path);

}  // namespace pt
