# Install rules: the one list of what `cmake --install` (and so colcon and the Debian package)
# puts where. The tools find their files relative to their own location (tools/io/data_dir.h):
# <prefix>/bin/vb_* read <prefix>/share/vb/{data,tasks,web}; so bin/ and share/vb are fixed
# relative to each other (not GNUInstallDirs variables that could move one without the other).
#
#   bin/                  vb_run vb_batch vb_gen vb_import vb_report vb_view vb_gym vb_collect
#   share/vb/data/        vehicles, soils, perception presets, the benchmark's height images
#   share/vb/tasks/       the 100 benchmark tasks (their height images: ../data/worlds/)
#   share/vb/web/viewer/  the 3-D viewer's static files (vb_view)
#   share/doc/vb/         README.md and docs/*.md with their pictures
#
# The build tree mirrors the layout: build/share/vb/{data,tasks,web} are RELATIVE symlinks to the
# source tree (e.g. ../../../data for build/ inside the checkout), so build/tools/vb_* find their
# files exactly as installed ones do, and a checkout copied or moved with its build tree reads its
# own data, never the original's (BuildTreeLayoutTest checks both).
set(VB_TOOLS vb_run vb_batch vb_gen vb_import vb_report vb_view vb_gym vb_collect)
install(TARGETS ${VB_TOOLS} RUNTIME DESTINATION bin)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION share/vb/data)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/tasks/ DESTINATION share/vb/tasks
        FILES_MATCHING PATTERN "*.yaml")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/web/viewer/ DESTINATION share/vb/web/viewer)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION share/doc/vb)
file(GLOB VB_USER_DOCS ${PROJECT_SOURCE_DIR}/docs/*.md)
install(FILES ${VB_USER_DOCS} DESTINATION share/doc/vb/docs)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/img/ DESTINATION share/doc/vb/docs/img)

file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/share/vb)
foreach(_d data tasks web)   # (re)made at every configure
  file(RELATIVE_PATH _target ${PROJECT_BINARY_DIR}/share/vb ${PROJECT_SOURCE_DIR}/${_d})
  file(REMOVE ${PROJECT_BINARY_DIR}/share/vb/${_d})
  file(CREATE_LINK ${_target} ${PROJECT_BINARY_DIR}/share/vb/${_d} SYMBOLIC)
endforeach()
