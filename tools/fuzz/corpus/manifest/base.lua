-- The base mod: Tumble's own scenarios, vehicles, emitters and bindings.
return {
  name = "base",
  version = "1.0.0",
  title = "Tumble base content",
  api = 1,
  depends = {},
}
