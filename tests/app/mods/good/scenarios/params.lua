-- param() reads --set values with the default's type.
return {
  duration = 0.1,
  on_start = function()
    expect("count from --set", param("count", 1), {min = 7, max = 7})
    expect("flag from --set", param("flag", false))
    expect("default when absent", param("absent", 2.5), {min = 2.5, max = 2.5})
  end,
}
