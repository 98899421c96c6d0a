# Smoke tests of the viewer under a virtual X server. Included from tests/CMakeLists.txt when
# the viewer is built.
if(TARGET trilab)
    set(TRILAB_XVFB xvfb-run -a -s "-screen 0 1280x800x24")
    # Three frames of the default model and a screenshot, exit status 0.
    add_test(NAME viewer_smoke
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --frames 3
                     --screenshot ${CMAKE_CURRENT_BINARY_DIR}/viewer_smoke.png)
    # A file loaded as a job, a render mode and a colouring with its legend.
    add_test(NAME viewer_modes
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab>
                     ${CMAKE_CURRENT_SOURCE_DIR}/data/good/header_variants.off
                     --mode hidden-line --color gaussian --frames 3
                     --screenshot ${CMAKE_CURRENT_BINARY_DIR}/viewer_modes.png)
    # The history starts with the file, not with the built-in model it replaced.
    set_tests_properties(viewer_modes PROPERTIES PASS_REGULAR_EXPRESSION
                         "loaded .*header_variants.off.*history: 0 Load header_variants.off\n")
    # A bad file: the viewer keeps the default model, says why (file and line), exits 0.
    add_test(NAME viewer_bad_file
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab>
                     ${CMAKE_CURRENT_SOURCE_DIR}/data/bad/off_nan.off --frames 2)
    set_tests_properties(viewer_bad_file PROPERTIES PASS_REGULAR_EXPRESSION "off_nan.off:4: ")
    # An operation applied after start-up becomes a history entry and plays its morph; the
    # last frame (and its screenshot) shows the end of the morph, the status bar the new state.
    add_test(NAME viewer_operation
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op "noise --amount 30" --color mean
                     --frames 2 --screenshot ${CMAKE_CURRENT_BINARY_DIR}/viewer_operation.png)
    set_tests_properties(viewer_operation PROPERTIES PASS_REGULAR_EXPRESSION
                         "last frame: state 1 of 2: Add noise --amount 30[^\n]*, morph t = 1.000\n.*status: state 1: Add noise")
    # --morph-t: the last frame shows the morph at that time.
    add_test(NAME viewer_morph_t
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op "noise --amount 30" --morph-t 0.25
                     --frames 2)
    set_tests_properties(viewer_morph_t PROPERTIES PASS_REGULAR_EXPRESSION
                         "last frame: state 1 of 2: Add noise[^\n]*, morph t = 0.250\n")
    # The automatic wireframe overlay: on for the default model (edges tens of pixels long),
    # off after three Loop steps (128,000 faces, edges a few pixels); --wireframe forces it.
    add_test(NAME viewer_wireframe_auto_on
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --frames 2)
    set_tests_properties(viewer_wireframe_auto_on PROPERTIES PASS_REGULAR_EXPRESSION
                         "wireframe overlay on \\(automatic")
    add_test(NAME viewer_wireframe_auto_off
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op "subdivide --iterations 3" --frames 2)
    set_tests_properties(viewer_wireframe_auto_off PROPERTIES PASS_REGULAR_EXPRESSION
                         "wireframe overlay off \\(automatic")
    add_test(NAME viewer_wireframe_forced
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op "subdivide --iterations 3"
                     --wireframe on --frames 2)
    set_tests_properties(viewer_wireframe_forced PROPERTIES PASS_REGULAR_EXPRESSION
                         "wireframe overlay on \\(on;")
    # --click presses what a user presses (issue 23): the Record button records (it shared
    # its section header's ID once), a menu item through its menu, a section opened on the
    # way; a widget that is not there fails the run with what is there.
    file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/viewer_click)
    add_test(NAME viewer_click_record
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op "noise --amount 30"
                     --click "Record/Record" --click "Morph/Before" --click "File/Save as"
                     --frames 3
             WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/viewer_click)
    set_tests_properties(viewer_click_record PROPERTIES PASS_REGULAR_EXPRESSION
                         "click Record/Record: queued StartRecording\n.*click Morph/Before: queued ShowMorphAt.*click File/Save as: pressed.*recorded 60 frames in trilab-frames")
    # Issue 38, item 9: a click right after a job waits for what the job enables (Record after
    # a two-level subdivision), follows a button that moves (Animate turning into Stop),
    # and scrolls a long sidebar to a section below the fold (Fairing, Decimation and
    # Frequency open push Morph and Decimate's button out of sight).
    add_test(NAME viewer_click_waits_and_scrolls
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op "subdivide --iterations 2"
                     --show record,fairing,decimation,frequency,morph --click "Record/Record"
                     --click "Morph/Before" --click "Decimation/Decimate" --frames 10
             WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/viewer_click)
    set_tests_properties(viewer_click_waits_and_scrolls PROPERTIES PASS_REGULAR_EXPRESSION
                         "click Record/Record: queued StartRecording\n.*click Morph/Before: queued ShowMorphAt.*click Decimation/Decimate: queued ApplyOperation")
    add_test(NAME viewer_click_missing
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --click "Fairing/Nope" --frames 2)
    set_tests_properties(viewer_click_missing PROPERTIES WILL_FAIL TRUE)
    add_test(NAME viewer_click_missing_says_what_is_there
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --click "Fairing/Nope" --frames 2)
    set_tests_properties(viewer_click_missing_says_what_is_there PROPERTIES
                         PASS_REGULAR_EXPRESSION "--click \"Fairing/Nope\": no such widget [(]there: [^)]*Smooth")
    # A sweep whose preview is refused ends with the error and a non-zero exit (it waited
    # forever once): Loop x8 of the default model would pass the 50-million-face limit.
    add_test(NAME viewer_sweep_refused
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --sweep "subdivide --scheme loop"
                     --param iterations --range 1:8:2)
    set_tests_properties(viewer_sweep_refused PROPERTIES WILL_FAIL TRUE TIMEOUT 60)
    # A sweep refuses what the command line refuses (issue 38, item 2): a preview that
    # diverged (explicit umbrella at step 30 on the default model stops early), and a parameter
    # that does not apply (Taubin takes no step).
    add_test(NAME viewer_sweep_diverging
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --sweep "smooth --iterations 3"
                     --param step --range 30:30:1)
    set_tests_properties(viewer_sweep_diverging PROPERTIES TIMEOUT 60
                         PASS_REGULAR_EXPRESSION "--sweep: the preview of .* stopped early")
    add_test(NAME viewer_sweep_diverging_exit
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --sweep "smooth --iterations 3"
                     --param step --range 30:30:1)
    set_tests_properties(viewer_sweep_diverging_exit PROPERTIES WILL_FAIL TRUE TIMEOUT 60)
    add_test(NAME viewer_sweep_not_applying
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --sweep "smooth --operator taubin"
                     --param step --range 0.1:1:3)
    set_tests_properties(viewer_sweep_not_applying PROPERTIES TIMEOUT 60
                         PASS_REGULAR_EXPRESSION "--sweep: .*step")
    add_test(NAME viewer_sweep_not_applying_exit
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --sweep "smooth --operator taubin"
                     --param step --range 0.1:1:3)
    set_tests_properties(viewer_sweep_not_applying_exit PROPERTIES WILL_FAIL TRUE TIMEOUT 60)
    add_test(NAME viewer_bad_wireframe COMMAND $<TARGET_FILE:trilab> --wireframe sometimes --frames 1)
    set_tests_properties(viewer_bad_wireframe PROPERTIES WILL_FAIL TRUE)
    # The layout rule (viewer_layout_check.cmake) with every panel open, a colour legend and a
    # history entry, at three framebuffer sizes and two UI scales; then with the dialogs open.
    foreach(size 1280x720 1920x1080 2560x1440)
        foreach(scale 1 2)
            add_test(NAME viewer_layout_${size}_scale${scale}
                     COMMAND ${CMAKE_COMMAND} -DTRILAB=$<TARGET_FILE:trilab> -DSIZE=${size}
                             -DSCALE=${scale}
                             "-DARGS=--show;all;--color;mean;--op;noise --amount 5"
                             "-DREQUIRE=Sidebar;History;Log;Status;##MainMenuBar;##legend"
                             -P ${CMAKE_CURRENT_SOURCE_DIR}/viewer_layout_check.cmake)
        endforeach()
    endforeach()
    add_test(NAME viewer_layout_dialogs
             COMMAND ${CMAKE_COMMAND} -DTRILAB=$<TARGET_FILE:trilab> -DSIZE=1280x720 -DSCALE=2
                     "-DARGS=--show;all,help,about,screenshot;--color;mean"
                     "-DDIALOGS=Key bindings;About trilab;Screenshot"
                     "-DREQUIRE=Sidebar;Key bindings;About trilab;Screenshot"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/viewer_layout_check.cmake)
    # The check itself fails on a window that overlaps another or leaves the framebuffer.
    foreach(bad overlap outside)
        add_test(NAME viewer_layout_check_refuses_${bad}
                 COMMAND ${CMAKE_COMMAND}
                         -DLAYOUT_FILE=${CMAKE_CURRENT_SOURCE_DIR}/data/layout/${bad}.txt
                         "-DDIALOGS=Key bindings"
                         -P ${CMAKE_CURRENT_SOURCE_DIR}/viewer_layout_check.cmake)
        set_tests_properties(viewer_layout_check_refuses_${bad} PROPERTIES WILL_FAIL TRUE)
    endforeach()
    add_test(NAME viewer_layout_check_accepts_dialog
             COMMAND ${CMAKE_COMMAND}
                     -DLAYOUT_FILE=${CMAKE_CURRENT_SOURCE_DIR}/data/layout/dialog_ok.txt
                     "-DDIALOGS=Key bindings"
                     -P ${CMAKE_CURRENT_SOURCE_DIR}/viewer_layout_check.cmake)
    add_test(NAME viewer_subdivision
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab>
                     --op "subdivide --scheme modified-butterfly --iterations 2"
                     --color subdivision --show subdivision,history --frames 10)
    set_tests_properties(viewer_subdivision PROPERTIES
                         PASS_REGULAR_EXPRESSION "Subdivide --scheme modified-butterfly")
    add_test(NAME viewer_fairing
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab>
                     --op "smooth --operator second-order --integration implicit --step 0.01 --iterations 3"
                     --show fairing --frames 10)
    set_tests_properties(viewer_fairing PROPERTIES PASS_REGULAR_EXPRESSION "Smooth --operator second-order")
    # Closing the window (pressed after frame 2, seen in frame 3): an unchanged document quits; unsaved changes ask first
    # (the modal stays open, so the run lasts its --frames).
    add_test(NAME viewer_close_unchanged
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --close-after 2 --frames 20)
    set_tests_properties(viewer_close_unchanged PROPERTIES PASS_REGULAR_EXPRESSION
                         "quit after 3 frames")
    add_test(NAME viewer_close_unsaved
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op "noise --amount 5" --close-after 3
                     --frames 12)
    set_tests_properties(viewer_close_unsaved PROPERTIES PASS_REGULAR_EXPRESSION
                         "unsaved changes: asking before quitting.*frames done")
    # The Frequency panel's path: a decomposition job, a band previewed and pushed as a
    # history entry, the frequency-mass colouring from the decomposition.
    add_test(NAME viewer_frequency
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --decompose 30:0:9 --color frequency-mass
                     --show frequency,history --frames 10
                     --screenshot ${CMAKE_CURRENT_BINARY_DIR}/viewer_frequency.png)
    set_tests_properties(viewer_frequency PROPERTIES
                         PASS_REGULAR_EXPRESSION "Frequency band 0:9 of 30")
    # --figure (issue 28): a reference figure's model and settings. Figure 1.12(c), the implicit
    # umbrella at step 20, smooths (an entry); 1.12(b), the explicit one, is stopped and
    # refused (no entry); an unknown name lists the figures.
    add_test(NAME viewer_figure_implicit
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --figure 1.12c --frames 3)
    set_tests_properties(viewer_figure_implicit PROPERTIES PASS_REGULAR_EXPRESSION
                         "history: 0 Figure 1.12c: default \\| 1 Smooth\n.*status: Figure 1.12c: Implicit umbrella")
    add_test(NAME viewer_figure_diverges
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --figure 1.12b --frames 3)
    set_tests_properties(viewer_figure_diverges PROPERTIES PASS_REGULAR_EXPRESSION
                         "history: 0 Figure 1.12b: default\n.*status: Smooth stopped early, nothing changed")
    add_test(NAME viewer_figure_unknown
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --figure 1.99 --frames 2)
    set_tests_properties(viewer_figure_unknown PROPERTIES PASS_REGULAR_EXPRESSION
                         "no reference figure '1.99'; the figures are 1.2b")
    # Decimation with its panel open and the collapsing-edges overlay drawn.
    add_test(NAME viewer_decimation
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab>
                     --op "decimate --cost quadric --percent 60 --iterations 2"
                     --show decimation,collapsing-edges,history --frames 10
                     --screenshot ${CMAKE_CURRENT_BINARY_DIR}/viewer_decimation.png)
    set_tests_properties(viewer_decimation PROPERTIES
                         PASS_REGULAR_EXPRESSION "Decimate --cost quadric --percent 60")
    # Tools > Flip orientation is a history entry; with --up z the spherical projection of
    # textured mode puts its poles on z (issue 16). A bad --up is refused.
    add_test(NAME viewer_up_axis_flip
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --op flip --up z --mode textured --frames 6)
    set_tests_properties(viewer_up_axis_flip PROPERTIES PASS_REGULAR_EXPRESSION
                         "volume 4.15508 -> -4.15508.*spherical, \\+z up texture coordinates")
    # --threads (issue 43): a bad count is refused naming the option; a good one runs.
    add_test(NAME viewer_bad_threads COMMAND $<TARGET_FILE:trilab> --threads many --frames 1)
    set_tests_properties(viewer_bad_threads PROPERTIES PASS_REGULAR_EXPRESSION
                         "trilab: --threads")
    add_test(NAME viewer_threads
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --threads 2 --op "smooth" --frames 3)
    set_tests_properties(viewer_threads PROPERTIES PASS_REGULAR_EXPRESSION "smooth .* done")
    add_test(NAME viewer_bad_up_axis COMMAND $<TARGET_FILE:trilab> --up x --frames 1)
    set_tests_properties(viewer_bad_up_axis PROPERTIES WILL_FAIL TRUE)
    add_test(NAME viewer_bad_operation COMMAND $<TARGET_FILE:trilab> --op "noise --amount -1"
                                              --frames 1)
    set_tests_properties(viewer_bad_operation PROPERTIES WILL_FAIL TRUE)
    # A bad option is refused.
    add_test(NAME viewer_bad_option COMMAND $<TARGET_FILE:trilab> --mode bogus --frames 1)
    set_tests_properties(viewer_bad_option PROPERTIES WILL_FAIL TRUE)
    # --pick: the model's centre is hit (the view's centre, right of the sidebar); two picks
    # measure. A pick in the window's corner is the background.
    add_test(NAME viewer_pick
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --pick 810,400 --pick 900,300 --frames 2)
    set_tests_properties(viewer_pick PROPERTIES PASS_REGULAR_EXPRESSION
                         "(^|\n)pick: vertex [0-9]+ edge [0-9]+ face [0-9]+ position [-0-9.e]+ [-0-9.e]+ [-0-9.e]+ ms [0-9.]+\n.*measure: straight [0-9.]+ geodesic [0-9.]+ path points [0-9]+")
    add_test(NAME viewer_pick_background
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --pick 1270,790 --frames 2)
    set_tests_properties(viewer_pick_background PROPERTIES PASS_REGULAR_EXPRESSION
                         "pick: nothing at 1270,790 \\(the background\\)")
    add_test(NAME viewer_pick_bad COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --pick 12x --frames 2)
    set_tests_properties(viewer_pick_bad PROPERTIES WILL_FAIL TRUE)
    # Sessions (issue 27): two --op saved with --save-session, listed by trilab-cli, opened
    # again (the same states, bit for bit, and settings); a killed viewer's journal restored
    # by --restore; --no-recovery writes none.
    add_test(NAME viewer_session
             COMMAND ${TRILAB_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/viewer/session_test.sh
                     $<TARGET_FILE:trilab> $<TARGET_FILE:trilab-cli>)
    set_tests_properties(viewer_session PROPERTIES PASS_REGULAR_EXPRESSION "session_test: save")
    # Recipes keep the viewer's selections; an empty selection is refused (issue 38, items 1, 10).
    add_test(NAME viewer_recipe_selection
             COMMAND ${TRILAB_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/viewer/recipe_test.sh
                     $<TARGET_FILE:trilab> $<TARGET_FILE:trilab-cli>)
    set_tests_properties(viewer_recipe_selection PROPERTIES PASS_REGULAR_EXPRESSION
                         "recipe_test: ok")
    # SIGKILL at 30 random moments of a scripted run: each journal restores a prefix of the
    # history bit for bit (tests/viewer/kill_test.sh).
    add_test(NAME viewer_kill_journal
             COMMAND ${TRILAB_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/viewer/kill_test.sh
                     $<TARGET_FILE:trilab> $<TARGET_FILE:trilab-cli> 30)
    set_tests_properties(viewer_kill_journal PROPERTIES TIMEOUT 120 PASS_REGULAR_EXPRESSION
                         "kill_test: every journal restored a prefix")
    # Real X input to the interactive viewer (issue 38 items 5 and 6; XTEST through ctypes,
    # tests/viewer/x_input.py): a drag during a slow exact frame turns the view and picks
    # nothing; the "simplified" note leaves the screen once the view rests after a morph.
    foreach(case drag-in-slow-frame note-after-morph)
        add_test(NAME viewer_x_input_${case}
                 COMMAND ${TRILAB_XVFB} python3 ${CMAKE_CURRENT_SOURCE_DIR}/viewer/x_input_test.py
                         $<TARGET_FILE:trilab> ${case})
        set_tests_properties(viewer_x_input_${case} PROPERTIES TIMEOUT 180
                             PASS_REGULAR_EXPRESSION "${case}: (turned, nothing picked|gone at rest)")
    endforeach()
    # Large meshes, simplified while moving (docs/viewer.md): TRILAB_PROXY_MIN_FACES (tests
    # only) lowers the proxy threshold so that the built-in model gets a proxy. After --orbit
    # the rested view equals the unturned view pixel for pixel (the view rectangle of both
    # screenshots; the status bar shows frame times), and the orbit drew the proxy.
    add_test(NAME viewer_orbit_rested_view
             COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/viewer_orbit_check.py
                     $<TARGET_FILE:trilab> ${CMAKE_CURRENT_BINARY_DIR}/viewer_orbit
                     --frames 3 --size 640x400)
    set_tests_properties(viewer_orbit_rested_view PROPERTIES TIMEOUT 240
                         ENVIRONMENT "TRILAB_PROXY_MIN_FACES=100"
                         PASS_REGULAR_EXPRESSION "the rested view equals the unturned view")
    # A large file's first picture (docs/viewer.md): clustered from the file's arrays while the
    # half-edge mesh is built, then the exact surface. TRILAB_PROXY_MIN_FACES makes the bunny
    # "large"; TRILAB_LOADING_PICTURE_HOLD_MS (tests only) keeps the load busy after its picture,
    # so that the picture is drawn on any machine. The picture comes first, the model after.
    # It needs the bunny of ../shared/meshes: without it the test says so and is skipped.
    set(trilab_bunny ${PROJECT_SOURCE_DIR}/../shared/meshes/stanford-bunny.obj)
    if(EXISTS ${trilab_bunny})
        add_test(NAME viewer_loading_picture_first
                 COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> ${trilab_bunny} --frames 3
                         --print-timing --no-recovery)
        set_tests_properties(viewer_loading_picture_first PROPERTIES TIMEOUT 120
                             ENVIRONMENT "TRILAB_PROXY_MIN_FACES=100;TRILAB_LOADING_PICTURE_HOLD_MS=800"
                             PASS_REGULAR_EXPRESSION "loading picture: automatic wireframe off .*simplified picture while loading: [0-9]+ triangles for 69451 faces\n.*loaded .*stanford-bunny.obj.*timing: first_frame_ms=[0-9]+ exact_frame_ms=[0-9]+")
    else()
        add_test(NAME viewer_loading_picture_first
                 COMMAND ${CMAKE_COMMAND} -E echo "skipped: ${trilab_bunny} is absent")
        set_tests_properties(viewer_loading_picture_first PROPERTIES
                             SKIP_REGULAR_EXPRESSION "skipped: ")
    endif()
    # A small mesh is always drawn exactly: every orbit frame exact, the note never shown.
    add_test(NAME viewer_orbit_small_exact
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --orbit 10 --frames 3 --print-timing)
    set_tests_properties(viewer_orbit_small_exact PROPERTIES
                         PASS_REGULAR_EXPRESSION "orbit: frames=10 median_ms=[0-9.]+ max_ms=[0-9.]+ rest_ms=[0-9.]+\norbit: proxy_frames=0 exact_frames=10.*timing: first_frame_ms=[0-9]+ exact_frame_ms=[0-9]+"
                         FAIL_REGULAR_EXPRESSION "simplified while moving")
    # The stand-in drawn while the view turns shows the state's selection (its weights sampled
    # through the stand-in's representatives; the tint is tested by pixels in
    # tests/render/test_proxy_view.cpp), and without a selection it shows none.
    add_test(NAME viewer_orbit_proxy_selection
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --select sphere:0,0,1,0.6 --orbit 6
                     --frames 3)
    set_tests_properties(viewer_orbit_proxy_selection PROPERTIES TIMEOUT 120
                         ENVIRONMENT "TRILAB_PROXY_MIN_FACES=100"
                         PASS_REGULAR_EXPRESSION "simplified while moving: [0-9]+ triangles for [0-9]+ faces \\(within [0-9.]+ px\\), with the selection\n.*orbit: proxy_frames=6")
    # In Textured mode the stand-in is drawn textured (its vertices take the texture
    # coordinates of their representatives; pixels in tests/render/test_proxy_view.cpp).
    add_test(NAME viewer_orbit_proxy_textured
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --mode textured --orbit 6 --frames 3)
    set_tests_properties(viewer_orbit_proxy_textured PROPERTIES TIMEOUT 120
                         ENVIRONMENT "TRILAB_PROXY_MIN_FACES=100"
                         PASS_REGULAR_EXPRESSION "simplified while moving: [0-9]+ triangles for [0-9]+ faces \\(within [0-9.]+ px\\), textured")
    add_test(NAME viewer_orbit_proxy_no_selection
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --orbit 6 --frames 3)
    set_tests_properties(viewer_orbit_proxy_no_selection PROPERTIES TIMEOUT 120
                         ENVIRONMENT "TRILAB_PROXY_MIN_FACES=100"
                         PASS_REGULAR_EXPRESSION "simplified while moving: [0-9]+ triangles"
                         FAIL_REGULAR_EXPRESSION "with the selection|textured")
    # The subdivision level slider dragged over computed levels shows each level's proxy while
    # it moves (2, 1, 2, ...), and the run ends on the exact surface.
    add_test(NAME viewer_sweep_levels_proxy
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --sweep "subdivide --scheme loop"
                     --param iterations --range 2:1:6)
    set_tests_properties(viewer_sweep_levels_proxy PROPERTIES TIMEOUT 120
                         ENVIRONMENT "TRILAB_PROXY_MIN_FACES=100"
                         PASS_REGULAR_EXPRESSION "simplified while moving: .*sweep: previews=6 ")
    # A fairing slider dragged over a large decomposition (here every mesh and decomposition
    # counts as large, and the worker takes 150 ms as on a large mesh): each move first shows
    # the clustered spectral prediction over the stand-in while the worker computes.
    add_test(NAME viewer_sweep_clustered_prediction
             COMMAND ${TRILAB_XVFB} $<TARGET_FILE:trilab> --decompose 30
                     --sweep "smooth --integration implicit" --param step --range 1:20:5)
    set_tests_properties(viewer_sweep_clustered_prediction PROPERTIES TIMEOUT 120
                         ENVIRONMENT "TRILAB_PROXY_MIN_FACES=100;TRILAB_ASYNC_PREDICTION_WORK=1;TRILAB_PREDICTION_WORKER_DELAY_MS=150"
                         PASS_REGULAR_EXPRESSION "spectral prediction drawn simplified while it is computed: [0-9]+ triangles.*sweep: previews=5 ")
    # Selections (issue 26): --select before --op and a timed --brush on the bunny (skipped
    # without ../shared/meshes).
    add_test(NAME viewer_selection_bunny
             COMMAND ${TRILAB_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/viewer/selection_test.sh
                     $<TARGET_FILE:trilab>
                     ${PROJECT_SOURCE_DIR}/../shared/meshes/stanford-bunny.obj)
    set_tests_properties(viewer_selection_bunny PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77)
    # --lasso on the bunny: the mouse's lasso, visible-only against through the model.
    add_test(NAME viewer_selection_lasso_bunny
             COMMAND ${TRILAB_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/viewer/selection_test.sh
                     $<TARGET_FILE:trilab>
                     ${PROJECT_SOURCE_DIR}/../shared/meshes/stanford-bunny.obj lasso)
    set_tests_properties(viewer_selection_lasso_bunny PROPERTIES TIMEOUT 120 SKIP_RETURN_CODE 77)
    add_test(NAME viewer_lasso_bad COMMAND $<TARGET_FILE:trilab> --lasso "600,300:700,x:650,400"
                                           --frames 1)
    set_tests_properties(viewer_lasso_bad PROPERTIES PASS_REGULAR_EXPRESSION
                         "--lasso \"600,300:700,x:650,400\": point 2 \\(\"700,x\"\\) is not X,Y")
endif()
