# SPDX-License-Identifier: BSD-3-Clause
# lmk_generate_ros_messages(PACKAGE NAME DIR DIR OUTPUT_DIR OUT [DEPENDS PKG...] HEADERS VAR)
# Generates the C++ headers of a ROS 1 message package from DIR/msg/*.msg, DIR/srv/*.srv and
# DIR/action/*.action into OUT/NAME/, with Debian's own generators (actionlib_msgs' genaction.py,
# then gencpp), so that lmk needs neither catkin nor the package installed. DEPENDS names the
# packages the definitions use; their .msg files are read from /usr/share/PKG/msg. VAR receives the
# generated headers, for a target to depend on.
set(LMK_ROS_PYTHON "/usr/bin/python3" CACHE FILEPATH
    "The python3 that runs ROS's generators (Debian's; another python3 lacks genmsg)")
set(LMK_ROS_SHARE "/usr/share" CACHE PATH "Where Debian's ROS packages keep their definitions")
find_file(LMK_GENACTION genaction.py PATHS /usr/lib/actionlib_msgs NO_DEFAULT_PATH)
find_file(LMK_GENCPP gen_cpp.py PATHS /usr/lib/gencpp NO_DEFAULT_PATH)
if(NOT LMK_GENACTION OR NOT LMK_GENCPP)
  message(FATAL_ERROR "lmk::ros needs ROS's message generators: install libactionlib-msgs-dev "
                      "and python3-gencpp (scripts/install-deps.sh), or configure with "
                      "-DLMK_WITH_ROS=OFF")
endif()

function(lmk_generate_ros_messages)
  cmake_parse_arguments(ARG "" "PACKAGE;DIR;OUTPUT_DIR;HEADERS" "DEPENDS" ${ARGN})
  set(pkg ${ARG_PACKAGE})
  set(action_dir "${CMAKE_CURRENT_BINARY_DIR}/ros_definitions/${pkg}/msg")
  set(header_dir "${ARG_OUTPUT_DIR}/${pkg}")

  # An action NAME becomes seven messages: NAMEAction, NAMEActionGoal, NAMEGoal and so on.
  file(GLOB actions "${ARG_DIR}/action/*.action")
  set(messages "")
  foreach(action ${actions})
    get_filename_component(name ${action} NAME_WE)
    set(generated "")
    foreach(suffix Action ActionGoal ActionResult ActionFeedback Goal Result Feedback)
      list(APPEND generated "${action_dir}/${name}${suffix}.msg")
    endforeach()
    add_custom_command(OUTPUT ${generated}
      COMMAND ${LMK_ROS_PYTHON} ${LMK_GENACTION} ${action}
              -o ${action_dir}
      DEPENDS ${action} COMMENT "Generating ${pkg}/${name} action messages" VERBATIM)
    list(APPEND messages ${generated})
  endforeach()
  file(GLOB definitions "${ARG_DIR}/msg/*.msg")
  list(APPEND messages ${definitions})
  file(GLOB services "${ARG_DIR}/srv/*.srv")

  set(include_flags -I ${pkg}:${ARG_DIR}/msg -I ${pkg}:${action_dir})
  foreach(dep ${ARG_DEPENDS})
    list(APPEND include_flags -I ${dep}:${LMK_ROS_SHARE}/${dep}/msg)
  endforeach()

  # Every header depends on all of the package's definitions: a message may embed any other.
  set(headers "")
  foreach(definition ${messages} ${services})
    get_filename_component(name ${definition} NAME_WE)
    set(outputs "${header_dir}/${name}.h")
    if(definition MATCHES "\\.srv$")
      list(APPEND outputs "${header_dir}/${name}Request.h" "${header_dir}/${name}Response.h")
    endif()
    add_custom_command(OUTPUT ${outputs}
      COMMAND ${LMK_ROS_PYTHON} ${LMK_GENCPP} ${definition}
              -p ${pkg} -o ${header_dir} -e ${LMK_ROS_SHARE}/gencpp ${include_flags}
      DEPENDS ${definition} ${messages} COMMENT "Generating ${pkg}/${name}" VERBATIM)
    list(APPEND headers ${outputs})
  endforeach()
  set(${ARG_HEADERS} ${headers} PARENT_SCOPE)
endfunction()

# lmk_generate_ros_python(PACKAGE NAME DIR DIR OUTPUT_DIR OUT [DEPENDS PKG...] TARGET T)
# Generates the Python side of a message package (issue #36: rospy and `rosservice call`) with
# Debian's genpy into OUT/NAME/msg and OUT/NAME/srv, each with its __init__.py, and a target T that
# builds them. OUT goes on PYTHONPATH; roslib also wants the package itself on ROS_PACKAGE_PATH
# (ros/msg/NAME/package.xml).
find_file(LMK_GENMSG_PY genmsg_py.py PATHS /usr/lib/genpy NO_DEFAULT_PATH)
find_file(LMK_GENSRV_PY gensrv_py.py PATHS /usr/lib/genpy NO_DEFAULT_PATH)

function(lmk_generate_ros_python)
  cmake_parse_arguments(ARG "" "PACKAGE;DIR;OUTPUT_DIR;TARGET" "DEPENDS" ${ARGN})
  if(NOT LMK_GENMSG_PY OR NOT LMK_GENSRV_PY)
    message(STATUS "lmk: python3-genpy is absent: no Python side of ${ARG_PACKAGE}")
    return()
  endif()
  set(pkg ${ARG_PACKAGE})
  set(include_flags -I ${pkg}:${ARG_DIR}/msg)
  foreach(dep ${ARG_DEPENDS})
    list(APPEND include_flags -I ${dep}:${LMK_ROS_SHARE}/${dep}/msg)
  endforeach()
  set(all_outputs "")
  # Every module depends on all of the package's messages, as the headers do: a message's md5sum,
  # and so a service's, covers every message it embeds.
  file(GLOB messages "${ARG_DIR}/msg/*.msg")
  foreach(kind msg srv)
    set(generator ${LMK_GENMSG_PY})
    if(kind STREQUAL "srv")
      set(generator ${LMK_GENSRV_PY})
    endif()
    file(GLOB definitions "${ARG_DIR}/${kind}/*.${kind}")
    set(out_dir "${ARG_OUTPUT_DIR}/${pkg}/${kind}")
    set(modules "")
    foreach(definition ${definitions})
      get_filename_component(name ${definition} NAME_WE)
      add_custom_command(OUTPUT "${out_dir}/_${name}.py"
        COMMAND ${LMK_ROS_PYTHON} ${generator} ${definition} -p ${pkg} -o ${out_dir}
                ${include_flags}
        DEPENDS ${definition} ${messages} COMMENT "Generating ${pkg}/${name} for Python" VERBATIM)
      list(APPEND modules "${out_dir}/_${name}.py")
    endforeach()
    add_custom_command(OUTPUT "${out_dir}/__init__.py"
      COMMAND ${LMK_ROS_PYTHON} ${generator} --initpy -p ${pkg} -o ${out_dir}
      DEPENDS ${modules} COMMENT "Generating ${pkg}.${kind} for Python" VERBATIM)
    list(APPEND all_outputs ${modules} "${out_dir}/__init__.py")
  endforeach()
  add_custom_command(OUTPUT "${ARG_OUTPUT_DIR}/${pkg}/__init__.py"
    COMMAND ${CMAKE_COMMAND} -E touch "${ARG_OUTPUT_DIR}/${pkg}/__init__.py"
    COMMENT "Generating the ${pkg} Python package" VERBATIM)
  list(APPEND all_outputs "${ARG_OUTPUT_DIR}/${pkg}/__init__.py")
  add_custom_target(${ARG_TARGET} ALL DEPENDS ${all_outputs})
endfunction()
