-- Test mod: scenes with known energy and momentum bookkeeping, for the run
-- report's error figures (tests/app/error_audit_test.cpp).
return {name = "audit", version = "0.1.0", title = "Error-figure test scenes", api = 1}
