-- Test mod: body definitions' inertia field (tests/scenarios/CMakeLists.txt).
return {name = "bodies", version = "0.1.0", title = "Body definition test scenarios", api = 1}
