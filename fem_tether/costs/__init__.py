"""What a kite system costs: Trevisi's cost model (ch. 6), LCOE and profit (eqs. 6.17, 7.1; Lourenço eq. 1.2)."""
