# Costs for ctest's order (tests/CMakeLists.txt includes this file after
# the tests are declared).
#
# ctest starts the longest tests first when it knows their times from an
# earlier run (Testing/Temporary/CTestCostData.txt). A fresh clone has
# none, and ctest would start the tests in the order they are declared:
# the golden, browser and Python tests, declared last, would run at the
# end, side by side (make test took 121 s in a fresh clone against 104 s
# with the times known). These are the tests of a second or more, with
# their seconds alone on a 2-core machine; a name that is no longer a test
# is ignored, and ctest's own data takes over after the first run.
# Made by: scripts/test-costs.py build > tests/test_costs.cmake
set_tests_properties("mpirun with 1 to 4 ranks gives the bytes of one process" PROPERTIES COST 8.6)
set_tests_properties("gallery in a headless browser" PROPERTIES COST 7.3)
set_tests_properties("memory estimates hold: peak RSS <= estimate <= 3 x peak, and --max-memory below refuses" PROPERTIES COST 7.3)
set_tests_properties("every code point goes through the line breaker, alone and beside others, in every language" PROPERTIES COST 5.2)
set_tests_properties("python: the example notebook runs headless" PROPERTIES COST 4.8)
set_tests_properties("hostile descriptions and options change nothing outside --out, and nothing at all when refused" PROPERTIES COST 4.3)
set_tests_properties("python: a progress callback that raises" PROPERTIES COST 3.9)
set_tests_properties("bad input gets one line naming the problem and what is allowed, exit status 2" PROPERTIES COST 3.5)
set_tests_properties("render --format, a list of png, pdf, svg, mp4 and frames, chooses what is written besides the PNG" PROPERTIES COST 3.3)
set_tests_properties("python: the figgen module" PROPERTIES COST 3.2)
set_tests_properties("a full disk gives a clear error and leaves no partial file" PROPERTIES COST 3.2)
set_tests_properties("a killed run started again computes only what is missing and gives the bytes of one run" PROPERTIES COST 3.2)
set_tests_properties("shards 1/3 2/3 3/3 and their merge give the bytes of one run" PROPERTIES COST 3.2)
set_tests_properties("SIGINT or SIGTERM during a render removes its temporaries and keeps earlier outputs" PROPERTIES COST 3.0)
set_tests_properties("two figgen processes rendering into one folder leave whole, matching files" PROPERTIES COST 2.9)
set_tests_properties("every test case of test_plant_figures" PROPERTIES COST 2.7)
set_tests_properties("a film is the same bytes on any number of threads, beside a CPU hog too" PROPERTIES COST 2.7)
set_tests_properties("1-D and 3-D patterns run, write VTI files VTK reads, and continue from them" PROPERTIES COST 2.5)
set_tests_properties("after a SIGKILL the next render into the folder removes what the killed one left" PROPERTIES COST 2.3)
set_tests_properties("wrap breaks where measuring every piece did, at every width" PROPERTIES COST 2.3)
set_tests_properties("every test case of test_chapter7" PROPERTIES COST 2.2)
set_tests_properties("python: the same bits as the command, gs-atlas" PROPERTIES COST 2.1)
set_tests_properties("100 steps of figgen equal Ready's from the same start" PROPERTIES COST 2.0)
set_tests_properties("gallery poster is the frame the description names and else the last frame" PROPERTIES COST 2.0)
set_tests_properties("flags, noncharacters, tags, surrogates and controls go through wrap as drawn" PROPERTIES COST 1.9)
set_tests_properties("every key of every catalog figure refuses a value outside what it allows, naming the key" PROPERTIES COST 1.8)
set_tests_properties("golden image fx-glider-3d (egl)" PROPERTIES COST 1.8)
set_tests_properties("the progress bar fits the terminal's width" PROPERTIES COST 1.8)
set_tests_properties("a failing rank ends the mpirun with one line naming it and its item" PROPERTIES COST 1.7)
set_tests_properties("a figure is the exact size asked for and only its film rounds to even as its JSON says" PROPERTIES COST 1.6)
set_tests_properties("gallery and thumbnails take --max-memory and hold an image's header to it" PROPERTIES COST 1.6)
set_tests_properties("golden image fx-pearson-map (egl)" PROPERTIES COST 1.5)
set_tests_properties("a 3-D film turns the camera round its last step after the run, the same bytes on any threads" PROPERTIES COST 1.4)
set_tests_properties("render --cmap recolours a field figure with matplotlib's colormap" PROPERTIES COST 1.4)
set_tests_properties("a film comes with a looping WebP preview that its JSON describes, the same bytes every run" PROPERTIES COST 1.4)
set_tests_properties("golden image pc-threshold (osmesa)" PROPERTIES COST 1.4)
set_tests_properties("python: the same bits as the command, bd-roughness" PROPERTIES COST 1.3)
set_tests_properties("golden image fx-fhn-labyrinth (egl)" PROPERTIES COST 1.3)
set_tests_properties("each tile of a formula atlas is the formula scene's run with its parameters" PROPERTIES COST 1.3)
set_tests_properties("render --format webm writes VP9 in WebM that decodes to every frame, the same bytes every run" PROPERTIES COST 1.3)
set_tests_properties("python: the same bits as the command, tc7-5" PROPERTIES COST 1.3)
set_tests_properties("python: the same bits as the command, pl-lsys-3d" PROPERTIES COST 1.2)
set_tests_properties("figgen's VTI file is read back by VTK with the same arrays, and continues the run" PROPERTIES COST 1.2)
set_tests_properties("a 1-D atlas tiles space-time diagrams and a 3-D one centre planes of the formula scene's runs" PROPERTIES COST 1.2)
set_tests_properties("every test case of test_snowflake_figures" PROPERTIES COST 1.2)
set_tests_properties("cmake --install puts figgen and the descriptions in a prefix, and the installed figgen reads them" PROPERTIES COST 1.1)
set_tests_properties("each document's own caption is drawn beneath its figure in its script" PROPERTIES COST 1.1)
set_tests_properties("golden image gs-atlas (egl)" PROPERTIES COST 1.1)
set_tests_properties("a merge refuses a part that is not as its shard wrote it, naming the folder and the item" PROPERTIES COST 1.1)
set_tests_properties("golden image pc-threshold (egl)" PROPERTIES COST 1.0)
set_tests_properties("python: the same bits as the command, fx-brusselator" PROPERTIES COST 1.0)
