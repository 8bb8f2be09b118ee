# End-to-end: both render forms, marker sheets, track, sweep + report with plots, and exit
# status 2 with a located message on bad input. Run by ctest as bench/cli_smoke.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

function(run expected_status)
  execute_process(COMMAND ${MARKERBENCH} ${ARGN} WORKING_DIRECTORY ${SOURCE_DIR}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL expected_status)
    message(FATAL_ERROR "markerbench ${ARGN}: status ${status}, expected ${expected_status}\n${out}\n${err}")
  endif()
  set(last_error "${err}" PARENT_SCOPE)
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

# --version names the build and the libraries; list names every tracker with its options
# and the marker files it reads, and every marker file with its readers.
run(0 --version)
if(NOT last_output MATCHES "^markerbench [^\n]+ \\(" OR NOT last_output MATCHES "\nOpenCV 4"
   OR NOT last_output MATCHES "\nzstd [0-9]")
  message(FATAL_ERROR "unexpected --version: ${last_output}")
endif()
run(0 list trackers)
foreach(expected
        "circle\n  reads: circle_d \\(circle_d\\), circle_e \\(circle_e\\), circle_f \\(circle_f\\)"
        "    tracking: true"
                 "apriltag  \\[isolated in sweeps by default\\]" "runetag\n  reads: runetag")
  if(NOT last_output MATCHES "${expected}")
    message(FATAL_ERROR "list trackers lacks '${expected}':\n${last_output}")
  endif()
endforeach()
run(0 list markers)
if(NOT last_output MATCHES "aruco: aruco DICT_6X6_250 id 0, 100 mm; read by aruco\n")
  message(FATAL_ERROR "unexpected list markers:\n${last_output}")
endif()
run(2 list sequences)

run(0 render scenarios/smoke.yaml --out ${WORK_DIR}/smoke)
if(NOT last_error MATCHES "render smoke 100% 8/8 frames")
  message(FATAL_ERROR "render printed no progress: ${last_error}")
endif()
file(STRINGS ${WORK_DIR}/smoke/groundtruth.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 9)
  message(FATAL_ERROR "smoke groundtruth.csv has ${n} lines, expected 9 (header + 8 frames)")
endif()
if(NOT EXISTS ${WORK_DIR}/smoke/frame_000007.png)
  message(FATAL_ERROR "frame_000007.png missing")
endif()

# The rendered folder is a dataset: score a tracker's estimates for it, then report on them.
foreach(f camera.yaml dataset.json README.txt markers/apriltag.yaml markers/circles_a.yaml)
  if(NOT EXISTS ${WORK_DIR}/smoke/${f})
    message(FATAL_ERROR "the dataset lacks ${f}")
  endif()
endforeach()
file(WRITE ${WORK_DIR}/estimates.csv "frame,status,r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n1,ok,1,0,0,0,-1,0,0,0,-1,0,0,0.6\n")
run(0 score ${WORK_DIR}/smoke --poses ${WORK_DIR}/estimates.csv --tracker mine --out ${WORK_DIR}/scored)
if(NOT last_error MATCHES "smoke: scored 8 frames of mine into .*; 7 had no estimate")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()
# With the plots: a scored run has no times and no bound (their axes say so).
run(0 report ${WORK_DIR}/scored)
foreach(f smoke.png smoke_rotation_time.png)
  if(NOT EXISTS ${WORK_DIR}/scored/${f})
    message(FATAL_ERROR "report of the scored run did not write ${f}")
  endif()
endforeach()
file(WRITE ${WORK_DIR}/estimates.csv "frame,status,r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n8,ok,1,0,0,0,-1,0,0,0,-1,0,0,0.6\n")
run(2 score ${WORK_DIR}/smoke --poses ${WORK_DIR}/estimates.csv --tracker mine --out ${WORK_DIR}/scored2)
if(NOT last_error MATCHES "estimates.csv:2: column 'frame': '8' is not a frame of the dataset")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()

run(0 render scenarios/smoke.yaml --out ${WORK_DIR}/limited --limit 3 --float)
if(NOT EXISTS ${WORK_DIR}/limited/frame_000002.exr)
  message(FATAL_ERROR "--float wrote no EXR")
endif()
file(GLOB limited ${WORK_DIR}/limited/*.png)
list(LENGTH limited n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "--limit 3 wrote ${n} images")
endif()

file(WRITE ${WORK_DIR}/poses.csv "r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n1,0,0,0,-1,0,0,0,-1,0,0,0.5\n")
run(0 render --marker scenarios/markers/circle_d.yaml --camera scenarios/cameras/default.yaml
    --poses ${WORK_DIR}/poses.csv --out ${WORK_DIR}/explicit --noise-var 0.01 --blur-sigma 1 --seed 3)
if(NOT EXISTS ${WORK_DIR}/explicit/frame_000000.png)
  message(FATAL_ERROR "explicit render wrote no image")
endif()
# groundtruth.csv ends with the frame's Cramér-Rao bound (seven numbers), or with seven empty
# fields under --no-crlb.
string(REPEAT ",[0-9][0-9.e+-]*" 7 bound_fields)
file(STRINGS ${WORK_DIR}/explicit/groundtruth.csv rows)
list(GET rows 1 row)
if(NOT row MATCHES "${bound_fields}$")
  message(FATAL_ERROR "explicit render's row has no bound: ${row}")
endif()
run(0 render --marker scenarios/markers/circle_d.yaml --camera scenarios/cameras/default.yaml
    --poses ${WORK_DIR}/poses.csv --out ${WORK_DIR}/explicit_unbound --no-crlb)
file(STRINGS ${WORK_DIR}/explicit_unbound/groundtruth.csv rows)
list(GET rows 1 row)
if(NOT row MATCHES ",,,,,,,$")
  message(FATAL_ERROR "--no-crlb left a bound in the row: ${row}")
endif()

# A render never mixes two runs: a folder in use is refused, --overwrite replaces a dataset
# (and nothing else), and the options of one form are refused in the other.
file(WRITE ${WORK_DIR}/explicit/stale.png "")
run(2 render scenarios/smoke.yaml --out ${WORK_DIR}/explicit)
if(NOT last_error MATCHES "explicit: not empty; choose a new --out, or pass --overwrite")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()
run(0 render scenarios/smoke.yaml --out ${WORK_DIR}/explicit --overwrite --limit 2)
file(GLOB images ${WORK_DIR}/explicit/*.png)
list(LENGTH images n)
if(NOT n EQUAL 2)
  message(FATAL_ERROR "--overwrite left ${n} images, expected the 2 new ones")
endif()
file(MAKE_DIRECTORY ${WORK_DIR}/notes)
file(WRITE ${WORK_DIR}/notes/mine.txt "keep")
run(2 render scenarios/smoke.yaml --out ${WORK_DIR}/notes --overwrite)
if(NOT last_error MATCHES "empties only a folder markerbench rendered" OR NOT EXISTS ${WORK_DIR}/notes/mine.txt)
  message(FATAL_ERROR "--overwrite touched a folder that was not a dataset: ${last_error}")
endif()
run(2 render scenarios/smoke.yaml --out ${WORK_DIR}/noisy --noise-var 0.1)
if(NOT last_error MATCHES "--noise-var is for the explicit form")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()
run(2 render scenarios/smoke.yaml --out ${WORK_DIR}/unbound --no-crlb)
if(NOT last_error MATCHES "--no-crlb is for the explicit form.*crlb: keys")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()
run(2 render --marker scenarios/markers/circle_d.yaml --camera scenarios/cameras/default.yaml
    --poses ${WORK_DIR}/poses.csv --out ${WORK_DIR}/limited_explicit --limit 1)
if(NOT last_error MATCHES "--limit applies to a scenario's frames")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()

file(WRITE ${WORK_DIR}/bad_poses.csv "r11,r12,r13,r21,r22,r23,r31,r32,r33,tx,ty,tz\n1,0,0,0,-1,0,0,0,-1,0,0,abc\n")
run(2 render --marker scenarios/markers/circle_d.yaml --camera scenarios/cameras/default.yaml
    --poses ${WORK_DIR}/bad_poses.csv --out ${WORK_DIR}/bad)
if(NOT last_error MATCHES "bad_poses.csv:2: column 'tz'")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()

file(WRITE ${WORK_DIR}/bad.yaml "name: bad\ncamera: ${SOURCE_DIR}/scenarios/cameras/default.yaml\n")
run(2 render ${WORK_DIR}/bad.yaml --out ${WORK_DIR}/bad)
if(NOT last_error MATCHES "bad.yaml.*key 'markers': missing")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()

run(0 markers --out ${WORK_DIR}/sheets --marker scenarios/markers/apriltag.yaml)
if(NOT EXISTS ${WORK_DIR}/sheets/apriltag.pdf)
  message(FATAL_ERROR "marker sheet missing")
endif()

# markers reads every file before it writes a sheet.
run(2 markers --out ${WORK_DIR}/no_sheets --marker scenarios/markers/apriltag.yaml
    --marker ${WORK_DIR}/bad.yaml)
if(NOT last_error MATCHES "bad.yaml" OR EXISTS ${WORK_DIR}/no_sheets)
  message(FATAL_ERROR "markers wrote before it had read every file: ${last_error}")
endif()

# Devices, folders and FIFOs are not files: a device would read as empty, a FIFO would block.
run(2 render --marker scenarios/markers/circle_d.yaml --camera scenarios/cameras/default.yaml
    --poses /dev/null --out ${WORK_DIR}/bad)
if(NOT last_error MATCHES "/dev/null: expected a regular file, got a character device")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()
run(2 render --marker scenarios/markers/circle_d.yaml --camera scenarios/cameras
    --poses ${WORK_DIR}/poses.csv --out ${WORK_DIR}/bad)
if(NOT last_error MATCHES "scenarios/cameras: expected a regular file, got a directory")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()

# An output folder that is a file, or an output file that is a folder.
foreach(command "sweep;scenarios/smoke.yaml" "render;scenarios/smoke.yaml"
        "markers;--marker;scenarios/markers/apriltag.yaml")
  run(2 ${command} --out ${WORK_DIR}/poses.csv)
  if(NOT last_error MATCHES "poses.csv: expected an output folder, but it is a file")
    message(FATAL_ERROR "${command}: unexpected message: ${last_error}")
  endif()
endforeach()
run(2 track --tracker apriltag --marker scenarios/markers/apriltag.yaml
    --camera scenarios/cameras/default.yaml --out ${WORK_DIR} ${WORK_DIR}/smoke/frame_000001.png)
if(NOT last_error MATCHES "expected a file, but it is a folder")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()

# track: the smoke scenario's frame 1 is the apriltag at a paired pose.
execute_process(COMMAND ${MARKERBENCH} track --tracker apriltag --marker scenarios/markers/apriltag.yaml
                --camera scenarios/cameras/default.yaml ${WORK_DIR}/smoke/frame_000001.png
                ${WORK_DIR}/smoke/frame_000000.png
                WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT out MATCHES "frame_000001.png,apriltag,ok,1," OR
   NOT out MATCHES "frame_000000.png,apriltag,not_detected,0,,,")
  message(FATAL_ERROR "track output unexpected (${status}):\n${out}\n${err}")
endif()
run(2 track --tracker nosuch --marker scenarios/markers/apriltag.yaml
    --camera scenarios/cameras/default.yaml ${WORK_DIR}/smoke/frame_000001.png)
if(NOT last_error MATCHES "unknown tracker 'nosuch'")
  message(FATAL_ERROR "unexpected message: ${last_error}")
endif()

# Every example sweeps; a render-only scenario renders, and sweeping it names what it lacks.
file(GLOB examples RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/scenarios/examples/*.yaml)
foreach(example ${examples})
  run(0 sweep ${example} --out ${WORK_DIR}/examples --threads 2)
endforeach()
file(GLOB render_only RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/scenarios/render_only/*.yaml)
foreach(scenario ${render_only})
  get_filename_component(name ${scenario} NAME_WE)
  run(0 render ${scenario} --out ${WORK_DIR}/render_only/${name} --limit 2)
  run(2 sweep ${scenario} --out ${WORK_DIR}/examples)
  if(NOT last_error MATCHES "key 'trackers': missing")
    message(FATAL_ERROR "unexpected message: ${last_error}")
  endif()
endforeach()
run(0 report ${WORK_DIR}/examples --no-plots)

# sweep + report end to end, with the plots (Debian python3-matplotlib).
run(0 sweep scenarios/smoke.yaml --out ${WORK_DIR}/sweep --threads 2)
run(0 report ${WORK_DIR}/sweep)
foreach(f summary.csv report.md manifest.json smoke.png smoke_rotation_time.png
          smoke_examples.png smoke/frames.csv
          smoke/timing.csv smoke/examples/circles_a.png smoke/examples/apriltag.png)
  if(NOT EXISTS ${WORK_DIR}/sweep/${f})
    message(FATAL_ERROR "sweep/report did not write ${f}")
  endif()
endforeach()
file(STRINGS ${WORK_DIR}/sweep/summary.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 5)
  message(FATAL_ERROR "summary.csv has ${n} lines, expected 5 (header + 2 trackers x 2 values)")
endif()
file(READ ${WORK_DIR}/sweep/report.md report)
# smoke is not one of the paper's scenarios: no claims of the paper, its own section.
if(report MATCHES "The paper's claims beside ours" OR NOT report MATCHES "!\\[smoke: error")
  message(FATAL_ERROR "report.md of the smoke run holds the paper's claims or lacks the plot")
endif()
