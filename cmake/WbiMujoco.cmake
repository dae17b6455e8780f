# MuJoCo (Debian libmujoco-dev, 2.2), optional: defines WBI_WITH_MUJOCO and, when
# found, the target wbi_mujoco (header <mujoco/mujoco.h> + libmujoco).
# Debian's mujocoConfig.cmake is not used: its imported target names
# /usr/include/libqhull_r/, which libmujoco-dev does not pull in, so CMake refuses
# any target that links it. MuJoCo's public headers do not include qhull.
if(NOT TARGET wbi_mujoco)
  find_path(WBI_MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
  find_library(WBI_MUJOCO_LIBRARY mujoco)
  if(WBI_MUJOCO_INCLUDE_DIR AND WBI_MUJOCO_LIBRARY)
    file(STRINGS ${WBI_MUJOCO_INCLUDE_DIR}/mujoco/mujoco.h version_line
         REGEX "#define mjVERSION_HEADER")
    string(REGEX MATCH "[0-9]+" WBI_MUJOCO_VERSION "${version_line}")
    add_library(wbi_mujoco INTERFACE IMPORTED GLOBAL)
    target_include_directories(wbi_mujoco INTERFACE ${WBI_MUJOCO_INCLUDE_DIR})
    target_link_libraries(wbi_mujoco INTERFACE ${WBI_MUJOCO_LIBRARY})
    set(WBI_WITH_MUJOCO ON CACHE INTERNAL "MuJoCo found")
    message(STATUS "wbi: MuJoCo found (mjVERSION_HEADER ${WBI_MUJOCO_VERSION}, "
                   "${WBI_MUJOCO_LIBRARY}), WBI_WITH_MUJOCO=ON")
  else()
    set(WBI_WITH_MUJOCO OFF CACHE INTERNAL "MuJoCo found")
    message(STATUS "wbi: MuJoCo not found, WBI_WITH_MUJOCO=OFF: what needs it is not built "
                   "or skips (scripts/install-deps installs libmujoco-dev)")
  endif()
endif()
