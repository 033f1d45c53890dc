# The seed scene: a body under gravity, wind and quadratic drag, once per integrator.
ALL_TARGETS += $(B)/seed

$(B)/seed: tools/seed.c $(LIB_A)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $< $(LIB_A) $(LDLIBS)
