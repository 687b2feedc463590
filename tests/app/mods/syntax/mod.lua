-- A valid manifest whose scenario does not compile.
return {name = "syntax", version = "0.1.0", title = "Syntax error test", api = 1}
