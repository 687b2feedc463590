-- Line 3 has a syntax error.
return {
  on_start = function() local x = = 1 end,
}
