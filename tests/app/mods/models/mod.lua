-- Test mod: scenarios that use models, good and bad (tests/app/models_cli_test.cpp).
return {name = "models", version = "0.1.0", title = "Model test scenarios", api = 1, depends = {"base >= 0.1"}}
