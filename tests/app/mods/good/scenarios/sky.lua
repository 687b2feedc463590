-- Nothing but sky: the reference picture for the render test.
return {duration = 0.1}
