-- An error inside contact(): the host stops with file:line and traceback; the world it
-- left is still consistent enough to draw.
-- expect: contact failed
-- expect: boom on contact
-- expect: picture written
-- args: --svg $OUT/error_contact.svg
function setup(world)
  world:set_gravity(0, -10)
  world:body{ type = "static", aabb = {5, 0.5}, y = -0.5, name = "ground" }
  world:body{ circle = 0.5, y = 2, name = "ball" }
end
function contact(world, e)
  if e.kind == "begin" then error("boom on contact") end
end
