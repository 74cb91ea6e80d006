# Finds the Debian packages the project builds with; a missing one stops the
# configure step with the apt-get command that installs it.
function(pt_missing what package)
  message(FATAL_ERROR "${what} was not found. Install it with:\n"
                      "    sudo apt-get install ${package}\n"
                      "or run scripts/setup.sh, which installs every dependency.")
endfunction()

find_package(nlohmann_json 3 QUIET)
if(NOT nlohmann_json_FOUND)
  pt_missing("nlohmann-json (JSON parser)" nlohmann-json3-dev)
endif()

find_package(tinyobjloader QUIET)
if(NOT tinyobjloader_FOUND)
  pt_missing("tinyobjloader (OBJ reader)" libtinyobjloader-dev)
endif()

find_package(tinyexr QUIET)
if(NOT tinyexr_FOUND)
  pt_missing("tinyexr (OpenEXR images)" libtinyexr-dev)
endif()

find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
find_library(STB_LIBRARY stb)
if(NOT STB_INCLUDE_DIR OR NOT STB_LIBRARY)
  pt_missing("stb (stb_image, stb_image_write)" libstb-dev)
endif()
add_library(pt_stb INTERFACE)
target_include_directories(pt_stb SYSTEM INTERFACE ${STB_INCLUDE_DIR})
target_link_libraries(pt_stb INTERFACE ${STB_LIBRARY})

if(PT_BUILD_TESTS)
  find_package(doctest QUIET)
  if(NOT doctest_FOUND)
    pt_missing("doctest (unit tests)" doctest-dev)
  endif()
endif()

# SHA-256 of the grader's reference cache entries (src/grade/reference_renders.cpp).
find_path(NETTLE_INCLUDE_DIR nettle/sha2.h)
find_library(NETTLE_LIBRARY nettle)
if(NOT NETTLE_INCLUDE_DIR OR NOT NETTLE_LIBRARY)
  pt_missing("nettle (SHA-256)" nettle-dev)
endif()
add_library(pt_nettle INTERFACE)
target_include_directories(pt_nettle SYSTEM INTERFACE ${NETTLE_INCLUDE_DIR})
target_link_libraries(pt_nettle INTERFACE ${NETTLE_LIBRARY})

find_package(Threads REQUIRED)
