# Impact (thesis §4.2): block B2 (1,280 spheres) thrown at 5 m/s into the bonded block B1 (9,594).
#   make -f Makefile.cases impact   cast both blocks (about 1 minute on two cores), run the impact
#                                   (20,000 steps of 6.43e-6 s; about 20 s on two threads with the energy log), fragments, broken bonds,
#                                   the energy balance, and PNG renders of four instants (dem-render
#                                   under xvfb-run)
IMP_DIR := $(OUT)/impact
IMP_GEN := workflows/impact/generate.toml
IMP_SCENE := workflows/impact/scene.toml
# The four instants rendered [s], and the box every render frames (the same for all, so that the
# pictures compare): B1's slab and B2's path.
IMP_TIMES := 0.03 0.06 0.09 0.1286
IMP_BOX := -0.4,0.0,0.0,0.3,0.6,0.45
IMP_RENDER := xvfb-run -a $(BIN)/dem-render --quiet --relative-time --range 0,5 --box $(IMP_BOX) --size 1024,768

$(IMP_DIR)/b1.h5: $(IMP_GEN) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(IMP_GEN) --out $@

$(IMP_DIR)/blocks.h5: $(IMP_GEN) $(IMP_DIR)/b1.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(IMP_GEN) --stage cast --in $(IMP_DIR)/b1.h5 --out $@

# A VTK frame every 10 ms (velocity; displacement from the start: the deformed shape), the
# health log every 100 steps (the broken bonds over time) and the energy log (the scene's
# energy_every: every 100 steps).
$(IMP_DIR)/impact.h5 $(IMP_DIR)/impact.health.csv $(IMP_DIR)/impact.energy.csv $(IMP_DIR)/vtk/impact_particles.pvd &: $(IMP_SCENE) $(IMP_DIR)/blocks.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(IMP_SCENE) --stage impact --in $(IMP_DIR)/blocks.h5 --out $(IMP_DIR)/impact.h5 \
	  --vtk $(IMP_DIR)/vtk --health-every 100

# Fragments at the end: groups of particles joined by intact bonds (docs/post.md).
$(IMP_DIR)/fragments.csv $(IMP_DIR)/fragments.vtu &: $(IMP_DIR)/impact.h5 $(BIN)/post-macro
	$(BIN)/post-macro --in $(IMP_DIR)/impact.h5 --fragments $(IMP_DIR)/fragments.csv --vtk $(IMP_DIR)/fragments.vtu

$(IMP_DIR)/fragments.png: $(IMP_DIR)/fragments.csv scripts/plot_fragments.py scripts/post_table.py
	$(PYTHON) scripts/plot_fragments.py $< $@

$(IMP_DIR)/broken_bonds.csv $(IMP_DIR)/broken_bonds.png &: $(IMP_DIR)/impact.health.csv scripts/broken_bonds.py scripts/run_log_figure.py
	$(PYTHON) scripts/broken_bonds.py $< $(IMP_DIR)/broken_bonds.csv $(IMP_DIR)/broken_bonds.png

# Where B2's kinetic energy goes: held, dissipated (dashpot, friction) and released by broken bonds.
$(IMP_DIR)/energy.png: $(IMP_DIR)/impact.energy.csv scripts/plot_energy.py scripts/run_log_figure.py scripts/post_table.py
	$(PYTHON) scripts/plot_energy.py $< $@

# Four instants coloured by speed [0, 5 m/s]: in perspective, and cut by the mid-plane of B2's
# path (y = 0.3 m, seen from +y).
IMP_PNGS := $(foreach t,$(IMP_TIMES),$(IMP_DIR)/render/perspective_$(t).png $(IMP_DIR)/render/cut_$(t).png)
IMP_CUT := --point 0.1,0.3,0.3 --normal 0,1,0
$(eval $(call render_rules,$(IMP_DIR),$(IMP_DIR)/vtk/impact_particles.pvd,IMP_RENDER,IMP_CUT))

.PHONY: impact impact-outputs
impact: build
	@$(MAKE) --no-print-directory -f $(SELF) impact-outputs
	@echo "impact: VTK series $(IMP_DIR)/vtk/impact_particles.pvd (velocity, displacement), fragments $(IMP_DIR)/fragments.csv/.png/.vtu"
	@echo "impact: broken bonds $(IMP_DIR)/broken_bonds.csv/.png, energy balance $(IMP_DIR)/impact.energy.csv and energy.png, renders $(IMP_DIR)/render/*.png"
impact-outputs: $(IMP_DIR)/fragments.png $(IMP_DIR)/broken_bonds.png $(IMP_DIR)/energy.png $(IMP_PNGS)
CASES += impact
