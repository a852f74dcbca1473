// Compiles tests/CMakeLists.txt's precompiled header once per preset; every test reuses it.
